"""``Pose``: a planar pose, and the frames it defines (REP 103: metres, radians, z up).

A pose is also a frame: ``frame.compose(local)`` takes a pose given in ``frame`` to the
frame ``frame`` is given in (``map`` ← ``base_link``), ``frame.inverse()`` goes the other
way, and ``pose.relative_to(frame)`` expresses a pose in ``frame``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from homebot.geometry.angles import wrap_angle

__all__ = ["Pose"]


@dataclass(frozen=True, slots=True)
class Pose:
    """A planar pose: position in metres and heading in radians."""

    x: float
    y: float
    theta: float = 0.0

    def xy(self) -> tuple[float, float]:
        return (self.x, self.y)

    def compose(self, local: Pose) -> Pose:
        """``local`` (a pose in this pose's frame) in the frame this pose is given in."""
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        return Pose(self.x + cos * local.x - sin * local.y,
                    self.y + sin * local.x + cos * local.y,
                    wrap_angle(self.theta + local.theta))

    def inverse(self) -> Pose:
        """The frame this pose is given in, seen from this pose: ``p.compose(p.inverse())``
        is the origin."""
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        return Pose(-cos * self.x - sin * self.y, sin * self.x - cos * self.y,
                    wrap_angle(-self.theta))

    def relative_to(self, frame: Pose) -> Pose:
        """This pose expressed in ``frame`` (both given in the same frame)."""
        return frame.inverse().compose(self)

    def apply(self, x: float, y: float) -> tuple[float, float]:
        """The point ``(x, y)`` of this pose's frame in the frame this pose is given in."""
        cos, sin = math.cos(self.theta), math.sin(self.theta)
        return (self.x + cos * x - sin * y, self.y + sin * x + cos * y)
