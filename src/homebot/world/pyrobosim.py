"""A homebot world from a pyrobosim world YAML: rooms, hallways, locations, objects, robot.

The mapping (documented in the README, "Bringing a pyrobosim world"):

- ``params.name`` is the world's name; names lose their underscores ("my_desk" is
  "my desk"), as people say them.
- A room's ``footprint`` (``polygon`` with ``coords``, or ``box`` with ``dims``, each
  with an optional ``offset``) is the room's polygon.
- A hallway is a room of its own (the corridor ``width`` wide along the straight line
  between the rooms' centroids for ``conn_method: auto``, or along ``conn_points``),
  with a door where it meets each room; ``is_open: false`` makes the doors closed and
  ``is_locked: true`` locked. ``conn_method: angle`` is not imported.
- A location is furniture in its ``parent`` room, centred at its ``pose`` (a list
  ``[x, y, z, yaw]`` or a ``position``/``rotation_eul`` mapping, ``relative_to`` a room);
  its footprint comes from a small table of pyrobosim's example categories (a yaw near
  90° swaps width and depth, since homebot's furniture is axis-aligned).
- An object lies on its ``parent`` location (the first, or most probable, of a list
  or ``choices``); pyrobosim's object ``category`` ("apple") is homebot's category,
  and an unnamed object is called by its category ("apple", then "apple 2").
- The first robot's ``pose`` (or its ``location`` room's centroid) is the robot's
  start; pyrobosim has no people, so one person, the operator, stands beside it.

Metadata files (``$DATA/...``) are pyrobosim's own and are not read.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from shapely.geometry import LineString, Point, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union

from homebot.errors import WorldError
from homebot.yamlfile import LocatedDocument, load_yaml_document

__all__ = ["world_from_pyrobosim"]

# Footprints (width along x, depth along y, in metres) of pyrobosim's example location
# categories; other categories get _DEFAULT_SIZE.
_SIZES: Mapping[str, tuple[float, float]] = {
    "table": (0.9, 1.2), "desk": (0.6, 0.6), "counter": (1.2, 0.6), "trash_can": (0.4, 0.4),
    "charger": (0.5, 0.5), "shelf": (1.0, 0.4), "bed": (1.6, 2.0), "sofa": (2.0, 0.9),
}
_DEFAULT_SIZE = (0.6, 0.6)
# homebot's kind of furniture for pyrobosim's location categories.
_FURNITURE = {"table": "table", "desk": "table", "counter": "table", "trash_can": "bin",
              "shelf": "storage", "bed": "seating", "sofa": "seating", "charger": "fixture"}


def world_from_pyrobosim(path: str | Path, *, operator: str = "Alex") -> dict[str, Any]:
    """Plain world data (for ``World.from_dict``) from a pyrobosim world file.

    Raises ``WorldError`` naming the file and the entry that cannot be imported.
    """
    source = Path(path)
    document = load_yaml_document(source, WorldError)
    data = document.data
    if not isinstance(data, Mapping) or not isinstance(data.get("rooms"), list) or not data[
            "rooms"]:
        raise WorldError(f"{source}: not a pyrobosim world; it needs a list of rooms with "
                         "footprints (pyrobosim docs: yaml/world_schema.rst)")
    return _Importer(source, document, operator).world()


class _Importer:
    def __init__(self, source: Path, document: LocatedDocument, operator: str) -> None:
        self.source = source
        self.document = document
        self.data: Mapping[str, Any] = document.data
        self.operator = operator
        self.rooms: dict[str, Polygon] = {}
        self.placements: dict[str, dict[str, Any]] = {}

    def fail(self, where: str, message: str) -> WorldError:
        """An error at ``where`` (``rooms[2] (kitchen).footprint``), with its line."""
        location: list[str | int] = []
        for step in re.sub(r" \([^)]*\)", "", where).split("."):
            name, _, index = step.partition("[")
            location.append(name)
            if index:
                location.append(int(index.rstrip("]")))
        line = self.document.line_of(location)
        return WorldError(f"{self.source}: line {line}: {where}: {message}")

    def world(self) -> dict[str, Any]:
        for index, room in enumerate(self.data["rooms"]):
            self._room(index, room)
        hallways, doors = self._hallways()
        placements = [self._location(index, entry)
                      for index, entry in enumerate(self.data.get("locations") or [])]
        objects = self._objects()
        categories = sorted({obj["category"] for obj in objects})
        robot = self._robot()
        person = {"name": self.operator, "room": _room_of(self.rooms, robot[:2]),
                  "position": _beside(self.rooms, robot)}
        params = self.data.get("params") or {}
        return {
            "name": _name(str(params.get("name") or self.source.stem)),
            "description": f"Imported from the pyrobosim world {self.source.name}.",
            "rooms": [{"name": name, "polygon": _corners(polygon)}
                      for name, polygon in {**self.rooms, **hallways}.items()],
            "doors": doors,
            "categories": [{"name": name, "plural": _plural(name)} for name in categories],
            "placements": placements,
            "objects": objects,
            "people": [person],
            "operator": self.operator,
            "robot": {"pose": [round(value, 3) for value in robot]},
        }

    # ------------------------------------------------------------ rooms and hallways

    def _room(self, index: int, entry: Any) -> None:
        where = f"rooms[{index}]"
        if not isinstance(entry, Mapping):
            raise self.fail(where, "a room is a mapping with a name and a footprint")
        name = _name(str(entry.get("name") or f"room {index}"))
        polygon = self._footprint(entry.get("footprint"), f"{where} ({name}).footprint")
        self.rooms[name] = polygon

    def _footprint(self, footprint: Any, where: str) -> Polygon:
        if not isinstance(footprint, Mapping):
            raise self.fail(where, "needs a footprint: {type: polygon, coords: [[x, y], ...]} "
                                   "or {type: box, dims: [w, h]}")
        kind = footprint.get("type")
        offset = _pair(footprint.get("offset", (0.0, 0.0)))
        if kind == "polygon":
            coords = footprint.get("coords")
            pairs = [_pair(point) for point in coords] if isinstance(coords, list) else []
            points = [pair for pair in pairs if pair is not None]
            if len(points) < 3 or len(points) < len(pairs):
                raise self.fail(where, "a polygon footprint needs three or more [x, y] coords")
            dx, dy = offset or (0.0, 0.0)
            polygon = Polygon([(x + dx, y + dy) for x, y in points])
        elif kind == "box":
            dims = _pair(footprint.get("dims"))
            if dims is None or dims[0] <= 0 or dims[1] <= 0:
                raise self.fail(where, "a box footprint needs dims: [width, height] above 0")
            half_w, half_h = dims[0] / 2, dims[1] / 2
            ox, oy = offset or (0.0, 0.0)
            polygon = Polygon([(ox - half_w, oy - half_h), (ox + half_w, oy - half_h),
                               (ox + half_w, oy + half_h), (ox - half_w, oy + half_h)])
        else:
            raise self.fail(where, f"footprint type '{kind}' is not imported; use polygon or box")
        if not polygon.is_valid or polygon.area <= 0:
            raise self.fail(where, "the footprint is not a simple area")
        return polygon

    def _hallways(self) -> tuple[dict[str, Polygon], list[dict[str, Any]]]:
        hallways: dict[str, Polygon] = {}
        doors: list[dict[str, Any]] = []
        for index, entry in enumerate(self.data.get("hallways") or []):
            where = f"hallways[{index}]"
            if not isinstance(entry, Mapping):
                raise self.fail(where, "a hallway is a mapping with room_start and room_end")
            start, end = (_name(str(entry.get(key, ""))) for key in ("room_start", "room_end"))
            for room in (start, end):
                if room not in self.rooms:
                    raise self.fail(where, f"unknown room '{room}'; rooms: "
                                           f"{', '.join(self.rooms)}")
            width = float(entry.get("width", 1.0))
            line = self._centreline(entry, start, end, where)
            others = unary_union(list(self.rooms.values()))
            corridor = _largest(line.buffer(width / 2, cap_style="flat").difference(others))
            if corridor is None:
                raise self.fail(where, "the hallway lies inside its rooms; move the rooms apart")
            name = f"{start} {end} hallway"
            hallways[name] = corridor
            state = "locked" if entry.get("is_locked") and entry.get("is_open") is False else (
                "closed" if entry.get("is_open") is False else "open")
            for room in (start, end):
                crossing = line.intersection(self.rooms[room].exterior)
                point = _nearest_point(crossing, corridor)
                if point is None:
                    raise self.fail(where, f"the hallway does not reach room '{room}'")
                doors.append({"name": f"{room} {end if room == start else start} door",
                              "rooms": [room, name], "position": [round(point.x, 3),
                                                                  round(point.y, 3)],
                              "width": round(min(3.0, max(0.45, width * 0.9)), 3),
                              "state": state})
        return hallways, doors

    def _centreline(self, entry: Mapping[str, Any], start: str, end: str,
                    where: str) -> LineString:
        method = entry.get("conn_method", "auto")
        if method == "auto":
            first, last = self.rooms[start].centroid, self.rooms[end].centroid
            return LineString([(first.x, first.y), (last.x, last.y)])
        if method == "points":
            pairs = [_pair(point) for point in entry.get("conn_points") or []]
            points = [pair for pair in pairs if pair is not None]
            if len(points) < 2 or len(points) < len(pairs):
                raise self.fail(where, "conn_points needs two or more [x, y] points")
            return LineString(points)
        raise self.fail(where, f"conn_method '{method}' is not imported; use auto or points")

    # ------------------------------------------------------------ locations and objects

    def _location(self, index: int, entry: Any) -> dict[str, Any]:
        where = f"locations[{index}]"
        if not isinstance(entry, Mapping):
            raise self.fail(where, "a location is a mapping with a category and a parent")
        category = str(entry.get("category") or "furniture")
        name = _name(str(entry.get("name") or f"{category} {index}"))
        room = _name(str(entry.get("parent", "")))
        if room not in self.rooms:
            raise self.fail(where, f"parent room '{room}' is not a room; rooms: "
                                   f"{', '.join(self.rooms)}")
        x, y, yaw = self._pose(entry.get("pose"), where, self.rooms[room].centroid)
        width, depth = _SIZES.get(category, _DEFAULT_SIZE)
        if abs(math.sin(yaw)) > math.sin(math.radians(45)):
            width, depth = depth, width
        placement = {"name": name, "category": _FURNITURE.get(category, "furniture"),
                     "room": room, "center": [round(x, 3), round(y, 3)],
                     "size": [width, depth]}
        self.placements[name] = placement
        return placement

    def _pose(self, pose: Any, where: str, centre: Point) -> tuple[float, float, float]:
        if pose is None:
            return centre.x, centre.y, 0.0
        if isinstance(pose, list) and len(pose) >= 2 and all(
                isinstance(value, (int, float)) for value in pose):
            yaw = float(pose[3]) if len(pose) >= 4 else 0.0
            return float(pose[0]), float(pose[1]), yaw
        if isinstance(pose, Mapping) and isinstance(pose.get("position"), Mapping):
            position = pose["position"]
            x, y = float(position.get("x", 0.0)), float(position.get("y", 0.0))
            rotation = pose.get("rotation_eul") or {}
            yaw = float(rotation.get("yaw", 0.0)) if isinstance(rotation, Mapping) else 0.0
            if isinstance(rotation, Mapping) and rotation.get("angle_units") == "degrees":
                yaw = math.radians(yaw)
            relative = pose.get("relative_to")
            if relative is not None:
                anchor = _name(str(relative))
                if anchor not in self.rooms:
                    raise self.fail(where, f"relative_to '{relative}' is not a room")
                origin = self.rooms[anchor].centroid
                x, y = x + origin.x, y + origin.y
            return x, y, yaw
        raise self.fail(where, "a pose is [x, y, z, yaw] or {position: {x, y}, rotation_eul: "
                               "{yaw}}")

    def _objects(self) -> list[dict[str, Any]]:
        objects: list[dict[str, Any]] = []
        taken: set[str] = set()
        for index, entry in enumerate(self.data.get("objects") or []):
            where = f"objects[{index}]"
            if not isinstance(entry, Mapping) or not entry.get("category"):
                raise self.fail(where, "an object is a mapping with a category and a parent")
            category = _name(str(entry["category"]))
            parent = _name(str(_first_choice(entry.get("parent"))))
            if parent not in self.placements:
                raise self.fail(where, f"parent '{parent}' is not a location; locations: "
                                       f"{', '.join(self.placements)}")
            name = _name(str(entry.get("name") or category))
            unique, number = name, 2
            while unique in taken:
                unique, number = f"{name} {number}", number + 1
            taken.add(unique)
            objects.append({"name": unique, "category": category, "placement": parent})
        return objects

    def _robot(self) -> tuple[float, float, float]:
        robots = self.data.get("robots") or []
        first = robots[0] if isinstance(robots, list) and robots else {}
        if not isinstance(first, Mapping):
            raise self.fail("robots[0]", "a robot is a mapping with a pose or a location")
        room = _name(str(_first_choice(first.get("location")) or ""))
        centre = self.rooms[room].centroid if room in self.rooms else next(
            iter(self.rooms.values())).centroid
        if first.get("pose") is None:
            return centre.x, centre.y, 0.0
        return self._pose(first["pose"], "robots[0].pose", centre)


def _name(text: str) -> str:
    return " ".join(text.replace("_", " ").split())


def _plural(category: str) -> str:
    if category.endswith(("s", "x", "ch", "sh")):
        return f"{category}es"
    if category.endswith("y") and category[-2:-1] not in set("aeiou"):
        return f"{category[:-1]}ies"
    return f"{category}s"


def _pair(value: Any) -> tuple[float, float] | None:
    if isinstance(value, (list, tuple)) and len(value) >= 2 and all(
            isinstance(item, (int, float)) for item in value[:2]):
        return float(value[0]), float(value[1])
    return None


def _first_choice(value: Any) -> Any:
    """A pyrobosim spawn choice: a name, a list (the first), or {choices, probabilities}."""
    if isinstance(value, list):
        return value[0] if value else None
    if isinstance(value, Mapping):
        choices = list(value.get("choices") or [])
        weights = list(value.get("probabilities") or [])
        if choices and len(weights) == len(choices):
            return choices[max(range(len(choices)), key=lambda i: float(weights[i]))]
        return choices[0] if choices else None
    return value


def _largest(shape: BaseGeometry) -> Polygon | None:
    polygons = [shape] if isinstance(shape, Polygon) else list(getattr(shape, "geoms", []))
    polygons = [polygon for polygon in polygons if isinstance(polygon, Polygon)
                and polygon.area > 1e-6]
    return max(polygons, key=lambda polygon: polygon.area) if polygons else None


def _nearest_point(crossing: BaseGeometry, corridor: Polygon) -> Point | None:
    points = [crossing] if isinstance(crossing, Point) else [
        geometry for geometry in getattr(crossing, "geoms", []) if isinstance(geometry, Point)]
    points = [point for point in points if corridor.exterior.distance(point) < 1e-6]
    return min(points, key=corridor.centroid.distance) if points else None


def _corners(polygon: Polygon) -> list[list[float]]:
    return [[round(x, 3), round(y, 3)] for x, y in list(polygon.exterior.coords)[:-1]]


def _room_of(rooms: Mapping[str, Polygon], point: tuple[float, float]) -> str:
    return next((name for name, polygon in rooms.items() if polygon.covers(Point(point))),
                next(iter(rooms)))


def _beside(rooms: Mapping[str, Polygon], robot: tuple[float, float, float]) -> list[float]:
    """A place 0.9 m to the robot's left, else right, else ahead, inside its room."""
    room = rooms[_room_of(rooms, robot[:2])]
    x, y, yaw = robot
    for angle in (math.pi / 2, -math.pi / 2, 0.0, math.pi):
        spot = Point(x + 0.9 * math.cos(yaw + angle), y + 0.9 * math.sin(yaw + angle))
        if room.buffer(-0.3).covers(spot):
            return [round(spot.x, 3), round(spot.y, 3)]
    return [round(x, 3), round(y, 3)]
