"""Pointing and "there": a pointing gesture picks a place on a surface (CAESAR Fig. 6).

A pointing gesture is a ray from the shoulder through the hand (map frame, metres,
z up). ``pointed_point`` intersects it with the surface's plane; ``pointed_place``
takes the named place the pointed point is closest to, by the fuzzy ``closeness``
read in the surface's frame, and asks (returns None) when two places are about as
close or none is near. ``deictic_request`` reads "put the red cup there".
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Final

from homebot.space.distance import closeness

__all__ = ["Pointing", "deictic_request", "pointed_place", "pointed_point"]

Point3 = tuple[float, float, float]

_REQUEST: Final = re.compile(
    r"^\s*(?:please\s+)?(?:put|place|set|move)\s+(?:the\s+)?(?P<what>[^\W\d][\w' -]*?)\s+"
    r"(?:there|over there|here)\s*(?:please)?\s*[.!]?\s*$", re.IGNORECASE)


@dataclass(frozen=True, slots=True)
class Pointing:
    """A pointing gesture: the shoulder and the hand of the pointing arm."""

    shoulder: Point3
    hand: Point3


def pointed_point(gesture: Pointing, height: float) -> tuple[float, float] | None:
    """Where the ray from shoulder through hand meets the plane ``z = height``; None when
    it points up or along the plane."""
    sx, sy, sz = gesture.shoulder
    dx, dy, dz = (gesture.hand[0] - sx, gesture.hand[1] - sy, gesture.hand[2] - sz)
    if dz >= -1e-9:
        return None
    along = (height - sz) / dz
    if along <= 0:
        return None
    return (sx + along * dx, sy + along * dy)


def pointed_place(gesture: Pointing, places: Mapping[str, tuple[float, float]], height: float,
                  scale: float, margin: float = 0.15) -> tuple[str | None, list[tuple[str, float]]]:
    """The place pointed at, and every place's closeness to the pointed point (best first).

    None when the gesture meets no plane, the best closeness is below 0.5 (pointing
    between or beyond the places), or the runner-up is within ``margin`` of it."""
    point = pointed_point(gesture, height)
    if point is None:
        return None, []
    scored = sorted(((name, closeness(math.dist(point, where), scale))
                     for name, where in places.items()), key=lambda pair: (-pair[1], pair[0]))
    best = scored[0][1]
    if best < 0.5 or (len(scored) > 1 and best - scored[1][1] < margin):
        return None, scored
    return scored[0][0], scored


def deictic_request(text: str) -> str | None:
    """What "put the red cup there" asks to put there (``red cup``); None for other words."""
    match = _REQUEST.match(text)
    return match["what"].strip().lower() if match else None
