"""Rays: where a pointing arm's ray meets a surface, how far it passes a point, and where
laser beams cross a line (map frame, metres, z up).

A pointing gesture is a ``Ray`` from the eyes (or the shoulder) through the hand.
Both resolvers of pointing use it: ``homebot.space.deixis`` for the named places on one
surface ("put it there"), ``homebot.perception.gestures`` for the placement or object
pointed at.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["Point3", "Ray", "nearest_by_angle", "rays_cross_line"]

#: a point in space: x, y, z in metres
Point3 = tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class Ray:
    """A ray from ``origin`` through ``through``, such as a pointing arm's."""

    origin: Point3
    through: Point3

    def direction(self) -> npt.NDArray[np.float64]:
        """The unit vector along the ray (zero length: the zero vector)."""
        direction = np.asarray(self.through, dtype=float) - np.asarray(self.origin, dtype=float)
        unit: npt.NDArray[np.float64] = direction / max(float(np.linalg.norm(direction)), 1e-9)
        return unit

    def meets_height(self, height: float) -> tuple[float, float, float] | None:
        """Where the ray meets the level plane ``z = height``, as (x, y, distance along the
        ray in metres); None when it points up or along the plane, or the plane is behind."""
        direction = self.direction()
        if direction[2] >= -1e-6:
            return None
        along = float((height - self.origin[2]) / direction[2])
        if along <= 0:
            return None
        return (float(self.origin[0] + along * direction[0]),
                float(self.origin[1] + along * direction[1]), along)

    def angle_to(self, point: Point3) -> float | None:
        """The angle in radians between the ray and the line from its origin to ``point``;
        None when ``point`` is the origin."""
        offset = np.asarray(point, dtype=float) - np.asarray(self.origin, dtype=float)
        distance = float(np.linalg.norm(offset))
        if distance < 1e-6:
            return None
        return math.acos(max(-1.0, min(1.0, float(offset @ self.direction()) / distance)))


def nearest_by_angle(ray: Ray, points: Mapping[str, Point3], within: float) -> str | None:
    """The name of the point at the smallest angle from ``ray``, if below ``within``
    radians (the first named on a tie); None when none is."""
    best, best_angle = None, within
    for name, point in points.items():
        angle = ray.angle_to(point)
        if angle is not None and angle < best_angle:
            best, best_angle = name, angle
    return best


def rays_cross_line(origin: npt.ArrayLike, directions: npt.ArrayLike, point: npt.ArrayLike,
                    normal: npt.ArrayLike) -> tuple[npt.NDArray[np.float64],
                                                    npt.NDArray[np.float64]]:
    """Where planar rays from ``origin`` along unit ``directions`` (n, 2) cross the line
    through ``point`` with unit ``normal``.

    Returns, per ray, the distance along it to the crossing and the crossing's offset
    along the line from ``point`` (to the left of ``normal``): a segment of the line is
    hit where the distance is positive and the offset within its half length. A ray
    along the line gives inf or nan; test for it with ``directions @ normal``.
    """
    origin = np.asarray(origin, dtype=float)
    directions = np.asarray(directions, dtype=float)
    point, normal = np.asarray(point, dtype=float), np.asarray(normal, dtype=float)
    along_line = np.array([-normal[1], normal[0]])
    with np.errstate(divide="ignore", invalid="ignore"):
        distance = ((point - origin) @ normal) / (directions @ normal)
        crossing = origin + distance[:, None] * directions
    offset: npt.NDArray[np.float64] = (crossing - point) @ along_line
    return distance, offset
