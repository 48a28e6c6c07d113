"""``Pose``: a planar pose, and the frames it defines (REP 103: metres, radians, z up).

A pose is also a frame: ``frame.compose(local)`` takes a pose given in ``frame`` out to
the frame ``frame`` is given in (``map`` ← ``base_link``), ``pose.relative_to(frame)``
goes the other way, and ``frame.inverse()`` is the outer frame seen from ``frame``.
``from_frame`` and ``to_frame`` do the same for arrays of points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from homebot.geometry.angles import wrap_angle

__all__ = ["Pose", "from_frame", "to_frame"]


@dataclass(frozen=True, slots=True)
class Pose:
    """A planar pose: position in metres and heading in radians."""

    x: float
    y: float
    theta: float = 0.0

    def xy(self) -> tuple[float, float]:
        return (self.x, self.y)

    def compose(self, local: Pose) -> Pose:
        """``local`` (a pose in this pose's frame) in the frame this pose is given in
        (``self ⊕ local``); the heading is wrapped."""
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        return Pose(self.x + cos * local.x - sin * local.y,
                    self.y + sin * local.x + cos * local.y,
                    wrap_angle(self.theta + local.theta))

    def relative_to(self, frame: Pose) -> Pose:
        """This pose seen from ``frame``, both given in the same frame (``frame⁻¹ ⊕ self``);
        the heading is wrapped."""
        dx, dy = self.x - frame.x, self.y - frame.y
        cos, sin = math.cos(frame.theta), math.sin(frame.theta)
        return Pose(cos * dx + sin * dy, -sin * dx + cos * dy, wrap_angle(self.theta - frame.theta))

    def inverse(self) -> Pose:
        """The frame this pose is given in, seen from this pose: ``p.compose(p.inverse())``
        is the origin."""
        return Pose(0.0, 0.0).relative_to(self)

    def apply(self, x: float, y: float) -> tuple[float, float]:
        """The point ``(x, y)`` of this pose's frame in the frame this pose is given in."""
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        return (self.x + cos * x - sin * y, self.y + sin * x + cos * y)


def from_frame(frame: Pose, points: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Points (n, 2 or more) given in ``frame``, in the frame ``frame`` is given in.

    Columns past the second (a height) are kept as they are: the turn is about z."""
    points = np.asarray(points, dtype=float)
    cos, sin = math.cos(frame.theta), math.sin(frame.theta)
    moved = points.copy()
    moved[:, 0] = frame.x + cos * points[:, 0] - sin * points[:, 1]
    moved[:, 1] = frame.y + sin * points[:, 0] + cos * points[:, 1]
    return moved


def to_frame(frame: Pose, points: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Points (n, 2 or more) given where ``frame`` is, seen from ``frame``: the inverse of
    ``from_frame``. Columns past the second are kept as they are."""
    points = np.asarray(points, dtype=float)
    cos, sin = math.cos(frame.theta), math.sin(frame.theta)
    dx, dy = points[:, 0] - frame.x, points[:, 1] - frame.y
    moved = points.copy()
    moved[:, 0] = cos * dx + sin * dy
    moved[:, 1] = -sin * dx + cos * dy
    return moved
