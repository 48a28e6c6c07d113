"""pyrobosim's geometry read into homebot's: poses, footprints, hallway corridors, boxes.

pyrobosim (``pyrobosim/utils/pose.py``, ``utils/polygon.py``, ``core/hallway.py``) places
a footprint by translating it to a pose and turning it about that point; a pose given
``relative_to`` another entity adds its position to the entity's and its yaw to the
entity's yaw (the offset is not turned). A hallway is its centre line buffered by half
its width with flat ends and mitred corners. These functions redo that arithmetic on
shapely geometry, and fit pyrobosim's turned footprints to homebot's axis-aligned ones.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeGuard

from shapely import affinity
from shapely.geometry import LineString, Point, Polygon, box
from shapely.geometry.base import BaseGeometry
from shapely.ops import linemerge, nearest_points, unary_union

__all__ = ["PlanarPose", "PoseFormatError", "aligned_box", "corridor", "free_point",
           "is_number", "parse_pose", "place_footprint", "shared_edge", "simple_footprint",
           "straight_hallway"]

#: how far apart two outlines may lie and still count as touching (rounding, noding)
TOUCHING = 1e-6


class PoseFormatError(ValueError):
    """A pose or footprint written in no form pyrobosim reads; the message says the forms."""


@dataclass(frozen=True)
class PlanarPose:
    """A pose on the floor: x, y (metres) and yaw (radians); roll and pitch dropped."""

    x: float
    y: float
    yaw: float = 0.0
    tilted: bool = False  #: the pose gave a roll or pitch, which the floor plan drops
    relative_to: str | None = None  #: the entity it is given relative to, if any

    def after(self, anchor: PlanarPose) -> PlanarPose:
        """This pose taken relative to ``anchor`` (pyrobosim's ``get_pose_relative_to``)."""
        return PlanarPose(self.x + anchor.x, self.y + anchor.y, self.yaw + anchor.yaw,
                          self.tilted)


def parse_pose(value: Any) -> PlanarPose:
    """A pose in any of pyrobosim's forms: ``[x, y]``, ``[x, y, z]``, ``[x, y, z, yaw]``,
    ``[x, y, z, roll, pitch, yaw]``, ``[x, y, z, qw, qx, qy, qz]``, or a mapping of
    ``position`` with ``rotation_eul`` (radians or ``angle_units: degrees``) or
    ``rotation_quat``, and an optional ``relative_to``."""
    if isinstance(value, list):
        if not all(is_number(item) for item in value) or len(value) not in (2, 3, 4, 6, 7):
            raise PoseFormatError("a pose list is [x, y], [x, y, z], [x, y, z, yaw], "
                                  "[x, y, z, roll, pitch, yaw] or [x, y, z, qw, qx, qy, qz]")
        numbers = [float(item) for item in value]
        if len(numbers) == 7:
            yaw, tilted = _quaternion_yaw(*numbers[3:])
            return PlanarPose(numbers[0], numbers[1], yaw, tilted)
        yaw = numbers[-1] if len(numbers) in (4, 6) else 0.0
        tilted = len(numbers) == 6 and (numbers[3] != 0 or numbers[4] != 0)
        return PlanarPose(numbers[0], numbers[1], yaw, tilted)
    if not isinstance(value, Mapping):
        raise PoseFormatError("a pose is {position: {x, y}, rotation_eul: {yaw}} or [x, y, z, "
                              "yaw]")
    position = value.get("position", {})
    if not isinstance(position, Mapping) or not all(
            is_number(position.get(axis, 0.0)) for axis in ("x", "y", "z")):
        raise PoseFormatError("position is a mapping of numbers x, y (and z)")
    yaw, tilted = 0.0, False
    quaternion, euler = value.get("rotation_quat"), value.get("rotation_eul")
    if quaternion is not None:
        if not isinstance(quaternion, Mapping) or not all(
                is_number(quaternion.get(axis, 0.0)) for axis in "wxyz"):
            raise PoseFormatError("rotation_quat is a mapping of numbers w, x, y, z")
        yaw, tilted = _quaternion_yaw(*(float(quaternion.get(axis, 0.0)) for axis in "wxyz"))
    elif euler is not None:
        if not isinstance(euler, Mapping) or not all(
                is_number(euler.get(axis, 0.0)) for axis in ("roll", "pitch", "yaw")):
            raise PoseFormatError("rotation_eul is a mapping of numbers roll, pitch, yaw")
        units = euler.get("angle_units", "radians")
        if units not in ("radians", "degrees"):
            raise PoseFormatError(f"angle_units '{units}' is neither radians nor degrees")
        scale = math.pi / 180 if units == "degrees" else 1.0
        yaw = float(euler.get("yaw", 0.0)) * scale
        tilted = bool(euler.get("roll", 0.0) or euler.get("pitch", 0.0))
    relative = value.get("relative_to")
    return PlanarPose(float(position.get("x", 0.0)), float(position.get("y", 0.0)), yaw,
                      tilted, None if relative is None else str(relative))


def simple_footprint(footprint: Any) -> tuple[Polygon, float | None]:
    """The polygon (in its own frame, ``offset`` applied) and height of a footprint of type
    ``polygon``, ``box`` or ``circle``. Other types raise ``PoseFormatError``."""
    if not isinstance(footprint, Mapping):
        raise PoseFormatError("a footprint is {type: polygon, coords: [[x, y], ...]}, "
                              "{type: box, dims: [w, h]} or {type: circle, radius: r}")
    kind = footprint.get("type")
    if kind == "polygon":
        coords = footprint.get("coords")
        if not isinstance(coords, list) or len(coords) < 3 or not all(
                isinstance(point, list) and len(point) >= 2 and all(
                    is_number(item) for item in point[:2]) for point in coords):
            raise PoseFormatError("a polygon footprint needs three or more [x, y] coords")
        polygon = Polygon([(float(point[0]), float(point[1])) for point in coords])
    elif kind == "box":
        dims = footprint.get("dims")
        if not (isinstance(dims, list) and len(dims) >= 2 and all(
                is_number(item) and item > 0 for item in dims[:2])):
            raise PoseFormatError("a box footprint needs dims: [width, height] above 0")
        polygon = box(-dims[0] / 2, -dims[1] / 2, dims[0] / 2, dims[1] / 2)
    elif kind == "circle":
        radius = footprint.get("radius")
        if not (is_number(radius) and radius > 0):
            raise PoseFormatError("a circle footprint needs a radius above 0")
        polygon = Point(0.0, 0.0).buffer(float(radius), quad_segs=8)
    else:
        raise PoseFormatError(f"footprint type '{kind}' is not one of polygon, box, circle")
    if not polygon.is_valid or polygon.area <= 0:
        raise PoseFormatError("the footprint is not a simple area; list its corners in order")
    offset = footprint.get("offset")
    if offset is not None:
        if not (isinstance(offset, list) and len(offset) in (2, 3) and all(
                is_number(item) for item in offset)):
            raise PoseFormatError("offset is [x, y] or [x, y, yaw]")
        shift = PlanarPose(float(offset[0]), float(offset[1]),
                           float(offset[2]) if len(offset) == 3 else 0.0)
        polygon = place_footprint(polygon, shift)
    height = footprint.get("height")
    return polygon, float(height) if is_number(height) and height > 0 else None


def place_footprint(polygon: Polygon, pose: PlanarPose) -> Polygon:
    """pyrobosim's ``transform_polygon``: translate to the pose, then turn about it."""
    moved = affinity.translate(polygon, pose.x, pose.y)
    turned: Polygon = affinity.rotate(moved, pose.yaw, origin=(pose.x, pose.y),
                                      use_radians=True)
    return turned


def corridor(points: Sequence[tuple[float, float]], width: float) -> Polygon:
    """A hallway's floor as pyrobosim draws it: the line buffered, flat ends, mitred bends."""
    shape = LineString(points).buffer(width / 2, cap_style="flat", join_style="mitre")
    return shape if isinstance(shape, Polygon) else Polygon()


def straight_hallway(start: tuple[float, float], end: tuple[float, float], offset: float,
                     angle: float | None) -> list[tuple[float, float]]:
    """The centre line of an ``auto`` hallway (``angle`` None) or an ``angle`` one, from the
    start room's centroid ``start`` towards the end room's ``end``, shifted ``offset``
    sideways; an angle keeps the length of the centroids' line projected on it
    (pyrobosim ``core/hallway.py``)."""
    theta = math.atan2(end[1] - start[1], end[0] - start[0])
    length = math.hypot(end[0] - start[0], end[1] - start[1])
    if angle is not None:
        length, theta = length * math.cos(theta - angle), angle
    cos, sin = math.cos(theta), math.sin(theta)
    x, y = start[0] - offset * sin, start[1] + offset * cos
    return [(x, y), (x + length * cos, y + length * sin)]


def shared_edge(first: Polygon, second: BaseGeometry) -> LineString | None:
    """The longest stretch of ``first``'s outline lying on ``second``'s, or None."""
    along = first.exterior.intersection(second.buffer(TOUCHING, join_style="mitre"))
    parts = [along] if isinstance(along, LineString) else [
        part for part in getattr(along, "geoms", []) if isinstance(part, LineString)]
    parts = [part for part in parts if not part.is_empty]
    if not parts:
        return None
    merged = linemerge(parts)
    lines = [merged] if isinstance(merged, LineString) else list(merged.geoms)
    lines = [line for line in lines if line.length > TOUCHING]
    return max(lines, key=lambda line: line.length) if lines else None


def aligned_box(footprint: Polygon, pose: PlanarPose, inside: BaseGeometry,
                others: Sequence[Polygon]) -> tuple[Polygon, float]:
    """The axis-aligned box homebot's furniture is, for a footprint (in its own frame)
    placed at ``pose``: the bounding box of the placed footprint, or the footprint turned
    to the nearest quarter turn instead (as large, and a better fit for a table turned
    101°), whichever keeps more of itself when shrunk about its centre as little as it
    takes to stay ``inside`` and clear of ``others``. Returns the box and the scale kept
    (1.0: the whole of it)."""
    blocked = unary_union(list(others)) if others else None

    def fits(candidate: Polygon) -> bool:
        if not inside.covers(candidate):
            return False
        return blocked is None or candidate.intersection(blocked).area <= TOUCHING

    def kept(candidate: Polygon) -> float:
        if fits(candidate):
            return 1.0
        low, high = 0.0, 1.0
        for _ in range(24):  # bisection to well under a millimetre
            middle = (low + high) / 2
            if fits(affinity.scale(candidate, middle, middle)):
                low = middle
            else:
                high = middle
        return low

    quarter = round(pose.yaw / (math.pi / 2)) * (math.pi / 2)
    candidates = [_bounding_box(place_footprint(footprint, pose)),
                  _bounding_box(place_footprint(footprint, PlanarPose(pose.x, pose.y,
                                                                      quarter)))]
    scored = [(kept(candidate), candidate) for candidate in candidates]
    scale, best = max(scored, key=lambda pair: (pair[0] ** 2 * pair[1].area, pair[0]))
    return affinity.scale(best, scale, scale), scale


def _bounding_box(shape: Polygon) -> Polygon:
    min_x, min_y, max_x, max_y = shape.bounds
    return box(min_x, min_y, max_x, max_y)


def free_point(area: BaseGeometry, target: tuple[float, float]) -> tuple[float, float] | None:
    """The point of ``area`` nearest ``target`` (``target`` itself when inside), or None."""
    if area.is_empty:
        return None
    point = Point(target)
    if area.covers(point):
        return target
    nearest = nearest_points(area, point)[0]
    return nearest.x, nearest.y


def _quaternion_yaw(w: float, x: float, y: float, z: float) -> tuple[float, bool]:
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    return yaw, abs(roll) > 1e-6 or abs(pitch) > 1e-6


def is_number(value: Any) -> TypeGuard[float]:
    """A finite number (not a bool), as YAML gives them."""
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(
        value)
