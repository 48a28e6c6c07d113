"""Qualitative orientation: eight sectors, intrinsic or relative reference (CAESAR Fig. 10b).

Granularity 3: 2³ = 8 sectors, centred every 45° counter-clockwise from the front:
``front``, ``front_left``, ``left``, ``back_left``, ``back``, ``back_right``,
``right``, ``front_right``. Memberships are triangles 45° wide on each side of a
sector's centre, so neighbouring sectors overlap, every direction's memberships
sum to 1, and halfway between two centres both hold with 0.5.

An orientation is read against a reference direction (REP 103: angles in radians,
counter-clockwise, "left" is +90°):

- **intrinsic**: the relatum's own front side (``Frame.front``): "behind the sofa"
  is on the side of the sofa away from where it faces;
- **relative**: a viewer's point of view: the relatum's front is the side facing the
  viewer, and left is the viewer's left: "the bottle behind the bowl" is further
  from the viewer than the bowl.
"""

from __future__ import annotations

import math
from typing import Final

from homebot.geometry import wrap_angle

__all__ = [
    "ORIENTATIONS",
    "SECTOR",
    "angle_between",
    "intrinsic_angle",
    "orientation_category",
    "orientation_memberships",
    "relative_angle",
    "side_degree",
]

#: the sectors, counter-clockwise from the front
ORIENTATIONS: Final = ("front", "front_left", "left", "back_left", "back", "back_right",
                       "right", "front_right")
SECTOR: Final = 2 * math.pi / len(ORIENTATIONS)  #: 45°: from one sector's centre to the next


def angle_between(angle: float, reference: float) -> float:
    """``angle - reference`` wrapped into [-π, π)."""
    return wrap_angle(angle - reference)


def orientation_memberships(angle: float) -> tuple[float, ...]:
    """The membership of a direction (radians from the front, counter-clockwise) in
    each sector of ``ORIENTATIONS``."""
    position = (angle % (2 * math.pi)) / SECTOR
    lower = int(position) % len(ORIENTATIONS)
    beyond = position - math.floor(position)
    degrees = [0.0] * len(ORIENTATIONS)
    degrees[lower] += 1.0 - beyond
    degrees[(lower + 1) % len(ORIENTATIONS)] += beyond
    return tuple(degrees)


def orientation_category(angle: float) -> str:
    """The sector a direction belongs to most."""
    degrees = orientation_memberships(angle)
    return ORIENTATIONS[max(range(len(degrees)), key=lambda index: degrees[index])]


def side_degree(angle: float, side: str) -> float:
    """How much a direction points to ``side`` (a sector), from 1 (its centre) down to 0
    (90° or more away): the sector's membership plus half of its two neighbours'."""
    if side not in ORIENTATIONS:
        raise ValueError(f"unknown orientation {side!r}; one of {', '.join(ORIENTATIONS)}")
    index = ORIENTATIONS.index(side)
    degrees = orientation_memberships(angle)
    count = len(ORIENTATIONS)
    return degrees[index] + 0.5 * (degrees[(index - 1) % count] + degrees[(index + 1) % count])


def intrinsic_angle(target: tuple[float, float], relatum: tuple[float, float],
                    front: float) -> float:
    """Direction of ``target`` seen from ``relatum``, against the relatum's front heading."""
    return angle_between(math.atan2(target[1] - relatum[1], target[0] - relatum[0]), front)


def relative_angle(target: tuple[float, float], relatum: tuple[float, float],
                   viewer: tuple[float, float], facing: float | None = None) -> float:
    """Direction of ``target`` from ``relatum`` as a viewer at ``viewer`` sees it.

    The relatum's front faces the viewer; left is the viewer's left. A target
    further away than the relatum on the viewer's line of sight is ``back``. The line
    of sight runs from the viewer to the relatum, or along ``facing`` (a heading) when
    given: a viewer looking at a table top as a whole, not at each thing in turn.
    """
    sight = facing if facing is not None else math.atan2(relatum[1] - viewer[1],
                                                         relatum[0] - viewer[0])
    seen = angle_between(math.atan2(target[1] - relatum[1], target[0] - relatum[0]), sight)
    # along the line of sight (away from the viewer) is "back", towards the viewer "front",
    # and the viewer's left stays left: a reflection of the viewer's angle
    return angle_between(math.pi - seen, 0.0)
