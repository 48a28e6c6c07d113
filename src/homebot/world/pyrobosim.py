"""A homebot world from a pyrobosim world YAML: rooms, hallways, locations, objects, robot.

``docs/worlds.md`` ("Bringing a pyrobosim world") lists what is imported as it is, what
is approximated (each with a warning naming the file, line and entry) and what is
refused (a ``WorldError`` naming them). In short:

- Rooms are their ``footprint`` (polygon, box or circle, with its ``offset``) placed by
  their ``pose`` (``relative_to`` an entity above it, or absolute).
- A hallway is pyrobosim's own corridor (``auto``, ``angle`` or ``points``, with its
  ``offset`` and ``width``) less the rooms it crosses: each piece is a room of its own,
  with a door wherever it meets a room.
- A location is furniture: its category's footprint from the metadata files beside the
  world, placed by its pose, as the axis-aligned box around it (homebot's furniture is
  axis-aligned), shrunk if that box would reach into a wall or other furniture.
- An object lies on its ``parent``: a location, an object spawn (``counter0_left``) or
  a location category; the first of a list, or the most probable of ``choices``.
- The first robot starts at its ``pose`` or its ``location``; one person, the operator,
  stands beside it (pyrobosim has no people).
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from shapely.geometry import Point, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union

from homebot.errors import WorldError
from homebot.world.pyrobosim_geometry import (
    TOUCHING,
    PlanarPose,
    PoseFormatError,
    aligned_box,
    corridor,
    free_point,
    is_number,
    parse_pose,
    place_footprint,
    shared_edge,
    simple_footprint,
    straight_hallway,
)
from homebot.world.pyrobosim_metadata import LocationCategory, read_location_metadata
from homebot.world.pyrobosim_schema import UnreadFields
from homebot.yamlfile import LocatedDocument, load_yaml_document

__all__ = ["PyrobosimImport", "import_pyrobosim"]

_WALL = 0.1  # homebot's wall_thickness (the default, kept in the world written)
_DOOR_MIN = 0.45  # homebot's narrowest door (its DoorModel wants more than 0.4 m)
_DOOR_MAX = 3.0
# homebot's names (its world model's Name): a letter, then letters, digits, space ' -
_SAYABLE = re.compile(r"[^\W\d_][\w '\-]*")
_SLIVER = 0.01  # m²: a piece of corridor smaller than this is no floor to stand on
_DEFAULT_CATEGORY = LocationCategory(Polygon([(-0.3, -0.3), (0.3, -0.3), (0.3, 0.3),
                                              (-0.3, 0.3)]))
# homebot's kind of furniture for pyrobosim's location categories.
_FURNITURE = {"table": "table", "desk": "desk", "counter": "counter", "trash_can": "bin",
              "trashcan_small": "bin", "trashcan_large": "bin", "shelf": "shelf",
              "storage": "storage", "bed": "seating", "sofa": "seating",
              "charger": "fixture"}

@dataclass
class PyrobosimImport:
    """A world read from a pyrobosim file, and what was approximated on the way."""

    data: dict[str, Any]  #: plain world data, for ``World.from_dict``
    #: one line per approximation: file, line, entry and what homebot made of it
    warnings: list[str] = field(default_factory=list)


def import_pyrobosim(path: str | Path, *, operator: str = "Alex") -> PyrobosimImport:
    """A homebot world (plain data, for ``World.from_dict``) from a pyrobosim world file.

    Raises ``WorldError`` naming the file, line and entry that cannot be imported.
    """
    source = Path(path)
    document = load_yaml_document(source, WorldError)
    data = document.data
    if not isinstance(data, Mapping) or not isinstance(data.get("rooms"), list) or not data[
            "rooms"]:
        raise WorldError(f"{source}: not a pyrobosim world; it needs a list of rooms with "
                         "footprints (pyrobosim docs: yaml/world_schema.rst)")
    importer = _Importer(source, document, operator)
    return PyrobosimImport(importer.world(), importer.warnings)


class _Importer:
    def __init__(self, source: Path, document: LocatedDocument, operator: str) -> None:
        self.source = source
        self.document = document
        self.data: Mapping[str, Any] = document.data
        self.operator = operator
        self.warnings: list[str] = []
        self.rooms: dict[str, Polygon] = {}
        self.corridors: dict[str, Polygon] = {}
        self.doors: list[dict[str, Any]] = []
        self.placements: dict[str, dict[str, Any]] = {}
        self.boxes: dict[str, Polygon] = {}  # placement name -> its axis-aligned footprint
        self.located: dict[str, str] = {}  # location as written ("trash") -> placement
        self.spawns: dict[str, str] = {}  # object spawn ("counter0 left") -> placement
        self.by_category: dict[str, list[str]] = defaultdict(list)
        self.dropped: set[str] = set()  # locations pyrobosim itself would not add
        self.poses: dict[str, PlanarPose] = {}  # entity name -> pose, for relative_to
        self.start_poses: dict[str, PlanarPose] = {}  # room -> its first nav pose
        self.labels: dict[tuple[str, int], str] = {}
        self.object_names: set[str] = set()
        self.unread = UnreadFields()

    # ------------------------------------------------------------ messages

    def _at(self, location: tuple[str | int, ...]) -> str:
        """``file: line N`` of the node at ``location``."""
        return f"{self.source}: line {self.document.line_of(list(location))}"

    def _where(self, location: tuple[str | int, ...]) -> str:
        """``file: line N: rooms[2] (kitchen).footprint``."""
        text = ""
        for position, step in enumerate(location):
            if isinstance(step, int):
                text += f"[{step}]"
                label = self.labels.get((str(location[position - 1]), step))
                text += f" ({label})" if label else ""
            else:
                text += f".{step}" if text else step
        return f"{self._at(location)}: {text or '(document)'}"

    def fail(self, location: tuple[str | int, ...], message: str) -> WorldError:
        return WorldError(f"{self._where(location)}: {message}")

    def warn(self, location: tuple[str | int, ...], message: str) -> None:
        self.warnings.append(f"{self._where(location)}: {message}")

    # ------------------------------------------------------------ the world

    def world(self) -> dict[str, Any]:
        self.unread.note((), "", self.data)
        params = self.data.get("params") or {}
        if isinstance(params, Mapping):
            self.unread.note(("params",), "params", params)
        metadata = self.data.get("metadata") or {}
        if isinstance(metadata, Mapping):
            self.unread.note(("metadata",), "metadata", metadata)
        self.categories = read_location_metadata(
            metadata.get("locations") if isinstance(metadata, Mapping) else None,
            self.source, lambda message: self.warn(("metadata",), message))
        for index, entry in enumerate(self.data["rooms"]):
            self._room(index, entry)
        for index, entry in enumerate(self._entries("hallways")):
            self._hallway(index, entry)
        for index, entry in enumerate(self._entries("locations")):
            self._location(index, entry)
        objects = [obj for index, entry in enumerate(self._entries("objects"))
                   if (obj := self._object(index, entry)) is not None]
        radius, robot = self._robot()
        person = self._operator_place(robot, radius)
        self.warnings += [f"{self._at(location)}: {message}"
                          for location, message in self.unread.report()]
        named = isinstance(params, Mapping) and params.get("name")
        return {
            "name": self._sayable(params["name"], ("params", "name")) if named else (
                _name(self.source.stem) if _SAYABLE.fullmatch(_name(self.source.stem))
                else "pyrobosim world"),
            "description": f"Imported from the pyrobosim world {self.source.name}.",
            "rooms": [{"name": name, "polygon": _corners(polygon)}
                      for name, polygon in {**self.rooms, **self.corridors}.items()],
            "doors": self.doors,
            "categories": [{"name": name, "plural": _plural(name)}
                           for name in sorted({obj["category"] for obj in objects})],
            "placements": list(self.placements.values()),
            "objects": objects,
            "people": [person],
            "operator": self.operator,
            "robot": {"pose": [round(robot.x, 3), round(robot.y, 3), round(robot.yaw, 4)],
                      "radius": radius},
        }

    def _entries(self, section: str) -> list[Any]:
        entries = self.data.get(section) or []
        if not isinstance(entries, list):
            raise self.fail((section,), f"{section} is a list of entries")
        return entries

    def _mapping(self, location: tuple[str, int], entry: Any, what: str) -> Mapping[str, Any]:
        if not isinstance(entry, Mapping):
            raise self.fail(location, f"each of {location[0]} is a mapping ({what})")
        self.unread.note(location, location[0], entry)
        return entry

    def _sayable(self, written: Any, location: tuple[str | int, ...]) -> str:
        """``written`` as homebot names it (``my_desk``: "my desk"), refused when it does
        not begin with a letter or holds other signs than letters, digits, ' and -."""
        name = _name(str(written))
        if not _SAYABLE.fullmatch(name):
            raise self.fail(location, f"'{written}' is no name homebot can say; begin it "
                                      "with a letter and use letters, digits, _, ' and -")
        return name

    def _pose(self, value: Any, location: tuple[str | int, ...]) -> PlanarPose:
        try:
            pose = parse_pose(value)
        except PoseFormatError as error:
            raise self.fail(location, str(error)) from None
        if pose.tilted:
            self.warn(location, "its roll and pitch are dropped; homebot's plan turns things "
                                "about the vertical only")
        if pose.relative_to is None:
            return pose
        anchor = self.poses.get(_name(pose.relative_to))
        if anchor is None:
            raise self.fail((*location, "relative_to"),
                            f"'{pose.relative_to}' is no room, location or object given "
                            f"above it; known: {', '.join(self.poses) or 'none'}")
        return pose.after(anchor)

    # ------------------------------------------------------------ rooms and hallways

    def _room(self, index: int, entry: Any) -> None:
        at: tuple[str | int, ...] = ("rooms", index)
        entry = self._mapping(("rooms", index), entry, "a name and a footprint")
        name = _unique(self._sayable(entry.get("name") or f"room{index}", (*at, "name")),
                       self.rooms)
        self.labels[("rooms", index)] = name
        footprint = entry.get("footprint")
        if isinstance(footprint, Mapping) and footprint.get("type") == "mesh":
            raise self.fail((*at, "footprint"), "a mesh footprint is not read; give the room "
                                                 "a polygon footprint (its outline)")
        try:
            polygon, _height = simple_footprint(footprint)
        except PoseFormatError as error:
            raise self.fail((*at, "footprint"), str(error)) from None
        pose = self._pose(entry["pose"], (*at, "pose")) if entry.get("pose") else None
        if pose is not None:
            polygon = place_footprint(polygon, pose)
        for other, shape in self.rooms.items():
            if polygon.buffer(-0.001).intersection(shape).area <= TOUCHING:
                continue  # touching, or overlapping by less than a millimetre
            trimmed = polygon.difference(shape)
            if not isinstance(trimmed, Polygon) or trimmed.area <= 0:
                raise self.fail(at, f"overlaps room '{other}' so that it falls apart; "
                                    "homebot's rooms do not overlap: move or shrink one")
            self.warn(at, f"overlaps room '{other}' by {polygon.area - trimmed.area:.2f} m²; "
                          f"the overlap is left to '{other}' (homebot's rooms do not overlap)")
            polygon = trimmed
        self.rooms[name] = polygon
        centre = polygon.centroid
        self.poses[name] = pose or PlanarPose(centre.x, centre.y)
        nav_poses = entry.get("nav_poses")
        if isinstance(nav_poses, list) and nav_poses:
            self.start_poses[name] = self._pose(nav_poses[0], (*at, "nav_poses", 0))

    def _hallway(self, index: int, entry: Any) -> None:
        at: tuple[str | int, ...] = ("hallways", index)
        entry = self._mapping(("hallways", index), entry, "room_start, room_end and width")
        start, end = (_name(str(entry.get(key, ""))) for key in ("room_start", "room_end"))
        self.labels[("hallways", index)] = f"{start} to {end}"
        for key, room in (("room_start", start), ("room_end", end)):
            if room not in self.rooms:
                raise self.fail((*at, key), f"unknown room '{room}'; rooms: "
                                             f"{', '.join(self.rooms)}")
        if start == end:
            raise self.fail((*at, "room_end"), f"a hallway joins two different rooms; it "
                                               f"starts and ends in '{start}'")
        width = entry.get("width")
        if not is_number(width) or width <= 0:
            raise self.fail((*at, "width"), "a hallway needs a width above 0, in metres")
        floor = corridor(self._centre_line(entry, start, end, at), float(width))
        if floor.is_empty or not floor.is_valid:
            raise self.fail(at, "the hallway's corridor is no simple area (its points "
                                "coincide or double back?); list conn_points along the way")
        state = "locked" if entry.get("is_locked") and entry.get("is_open") is False else (
            "closed" if entry.get("is_open") is False else "open")
        if float(width) < _DOOR_MIN:
            self.warn((*at, "width"), f"{width:g} m wide; homebot's doors are at least "
                                       f"{_DOOR_MIN:g} m, so its doors are drawn that wide")
        neighbours = {**self.rooms, **self.corridors}
        taken = unary_union(list(neighbours.values()))
        base = f"{start} {end} hallway"
        pieces = [piece for piece in _polygons(floor.difference(taken)) if piece.area > _SLIVER]
        doors: list[dict[str, Any]] = []
        if not pieces:  # the rooms meet inside the corridor: one door between them
            doors += self._doors_between(end, self.rooms[end], start,
                                         self.rooms[start].intersection(floor), state,
                                         f"{start} {end} door", float(width))
        for piece in sorted(pieces, key=lambda shape: -shape.area):
            name = _unique(base, {**self.rooms, **self.corridors})
            piece_doors: list[dict[str, Any]] = []
            for other, shape in neighbours.items():
                door_name = (f"{other} {end if other == start else start} door"
                             if other in (start, end) else f"{other} {base} door")
                piece_doors += self._doors_between(name, piece, other, shape, state,
                                                   door_name, float(width))
            if piece_doors:
                self.corridors[name] = piece
                doors += piece_doors
            else:
                self.warn(at, f"a piece of its corridor ({piece.area:.2f} m²) meets no room "
                              "over enough for a door; it is left out")
        reached = {room for door in doors for room in door["rooms"]}
        unreached = [(key, room) for key, room in (("room_start", start), ("room_end", end))
                     if room not in reached]
        # a room the corridor stops short of is the trouble, not one it starts inside
        for key, room in sorted(unreached, key=lambda pair: -floor.distance(
                self.rooms[pair[1]])):
            raise self.fail((*at, key), self._unreached(room, floor))
        self.doors += doors

    def _doors_between(self, first: str, first_shape: Polygon, second: str,
                       second_shape: BaseGeometry, state: str, name: str,
                       width: float) -> list[dict[str, Any]]:
        edge = shared_edge(first_shape, second_shape)
        if edge is None or edge.length < min(_DOOR_MIN, 0.9 * width):
            return []
        middle = edge.interpolate(0.5, normalized=True)
        return [{"name": _unique(name, {door["name"] for door in self.doors}),
                 "rooms": [second, first], "position": [round(middle.x, 3),
                                                        round(middle.y, 3)],
                 "width": round(min(_DOOR_MAX, max(_DOOR_MIN, min(edge.length, width))), 3),
                 "state": state}]

    def _unreached(self, room: str, floor: Polygon) -> str:
        shape = self.rooms[room]
        gap = floor.distance(shape)
        if gap > TOUCHING:
            return (f"the hallway's corridor ends {gap:.2f} m short of room '{room}'; move "
                    "its conn_points (or its offset and conn_angle) so that it reaches the "
                    "room")
        edges = [shared_edge(piece, shape) for piece in _polygons(floor.difference(shape))]
        length = max((edge.length for edge in edges if edge is not None), default=0.0)
        return (f"the hallway's corridor meets room '{room}' over only {length:.2f} m, too "
                f"little for a door ({_DOOR_MIN:g} m); widen it or lead it into the room")

    def _centre_line(self, entry: Mapping[str, Any], start: str, end: str,
                     at: tuple[str | int, ...]) -> list[tuple[float, float]]:
        method = entry.get("conn_method", "auto")
        if method == "points":
            points = entry.get("conn_points")
            if not isinstance(points, list) or len(points) < 2 or not all(
                    isinstance(point, list) and len(point) >= 2 and all(
                        is_number(item) for item in point[:2]) for point in points):
                raise self.fail((*at, "conn_points"), "conn_points needs two or more "
                                                       "[x, y] points")
            return [(float(point[0]), float(point[1])) for point in points]
        if method not in ("auto", "angle"):
            raise self.fail((*at, "conn_method"), f"conn_method '{method}' is not one of "
                                                   "auto, angle, points")
        offset, angle = entry.get("offset", 0.0), entry.get("conn_angle", 0.0)
        if not is_number(offset) or not is_number(angle):
            raise self.fail(at, "offset and conn_angle are numbers (metres, radians)")
        first, last = self.rooms[start].centroid, self.rooms[end].centroid
        return straight_hallway((first.x, first.y), (last.x, last.y), float(offset),
                                float(angle) if method == "angle" else None)

    # ------------------------------------------------------------ locations and objects

    def _location(self, index: int, entry: Any) -> None:
        at: tuple[str | int, ...] = ("locations", index)
        entry = self._mapping(("locations", index), entry, "a category and a parent room")
        category = str(entry.get("category") or "location")
        count = len(self.by_category[category])  # pyrobosim counts the ones it added
        written = str(entry.get("name") or f"{category}{count}")
        name = self._sayable(written, (*at, "name"))
        self.labels[("locations", index)] = name
        room = _name(str(entry.get("parent", "")))
        if room not in self.rooms:
            raise self.fail((*at, "parent"), f"parent room '{room}' is not a room; rooms: "
                                              f"{', '.join(self.rooms)}")
        kind = self.categories.get(category)
        if kind is None:
            self.warn((*at, "category"), f"'{category}' is in no location metadata read; "
                                          "it is taken as a 0.6 m square")
            kind = _DEFAULT_CATEGORY
        elif kind.approximated:
            self.warn((*at, "category"), f"'{category}': {kind.approximated}")
        pose = self._location_pose(entry, at, room, kind)
        footprint = place_footprint(kind.footprint, pose)
        if not footprint.buffer(-0.001).within(self.rooms[room]):
            self.dropped.add(name)
            self.warn(at, f"does not lie inside room '{room}' at ({pose.x:g}, {pose.y:g}); "
                          "pyrobosim does not add it either, so it is left out")
            return
        if name in self.rooms or name in self.corridors:  # homebot's names are one space
            renamed = _unique(f"{name} {_name(category)}", self.placements)
            self.warn((*at, "name"), f"'{name}' is also a room; the furniture is called "
                                      f"'{renamed}'")
            name = renamed
        self._furniture(at, entry, name, room, category, kind, pose)
        self.located[_name(written)] = name
        self.poses[_name(written)] = pose
        self.by_category[category].append(name)
        for spawn in kind.spawns:
            self.spawns[_name(f"{written}_{spawn}")] = name
            self.poses.setdefault(_name(f"{written}_{spawn}"), pose)

    def _location_pose(self, entry: Mapping[str, Any], at: tuple[str | int, ...], room: str,
                       kind: LocationCategory) -> PlanarPose:
        if entry.get("pose") is not None:
            return self._pose(entry["pose"], (*at, "pose"))
        # pyrobosim samples a free pose; homebot takes the free one nearest the centre,
        # a robot's width and more away from other furniture.
        min_x, min_y, max_x, max_y = kind.footprint.bounds
        reach = math.hypot(max_x - min_x, max_y - min_y) / 2
        area: BaseGeometry = self.rooms[room].buffer(-(_WALL / 2 + reach))
        others = list(self.boxes.values())
        if others:
            area = area.difference(unary_union(others).buffer(reach + 0.4))
        centre = self.rooms[room].centroid
        point = free_point(area, (centre.x, centre.y))
        if point is None:
            raise self.fail(at, f"has no pose and room '{room}' has no free place for it; "
                                "give it a pose")
        middle = kind.footprint.centroid
        pose = PlanarPose(point[0] - middle.x, point[1] - middle.y)
        self.warn(at, f"has no pose (pyrobosim picks one at random); homebot puts it at "
                      f"({pose.x:.2f}, {pose.y:.2f})")
        return pose

    def _furniture(self, at: tuple[str | int, ...], entry: Mapping[str, Any], name: str,
                   room: str, category: str, kind: LocationCategory,
                   pose: PlanarPose) -> None:
        inside = self.rooms[room].buffer(-_WALL / 2, join_style="mitre")
        shape, scale = aligned_box(kind.footprint, pose, inside, list(self.boxes.values()))
        min_x, min_y, max_x, max_y = shape.bounds
        width, depth = round(max_x - min_x, 3), round(max_y - min_y, 3)
        if width < 0.05 or depth < 0.05:
            raise self.fail(at, f"there is no room for it in '{room}' once homebot's walls "
                                f"({_WALL:g} m) and the furniture before it are drawn; move it")
        quarter_turns = pose.yaw / (math.pi / 2)
        turned = abs(quarter_turns - round(quarter_turns)) > 0.02 and not _is_round(
            kind.footprint)
        if turned or scale < 0.99:
            why = [f"turned {math.degrees(pose.yaw):.0f}° (homebot's furniture is "
                   "axis-aligned, so it is the box around it or turned square)"] if turned \
                else []
            if scale < 0.99:
                why.append(f"shrunk to {scale:.0%} to keep out of the walls and other "
                           "furniture")
            self.warn(at, f"its footprint is the {width:g} × {depth:g} m box around it, "
                          f"{' and '.join(why)}")
        if entry.get("is_open") is False:
            self.warn((*at, "is_open"), "closed: homebot's furniture has no doors, so it is "
                                         "imported open (what lies in it in plain view)")
        placement: dict[str, Any] = {
            "name": name, "category": _FURNITURE.get(category, "furniture"), "room": room,
            "center": [round((min_x + max_x) / 2, 3), round((min_y + max_y) / 2, 3)],
            "size": [width, depth]}
        if kind.height is not None and 0 < kind.height <= 2.5:
            placement["height"] = kind.height
        if name in self.placements:
            raise self.fail((*at, "name"), f"'{name}' is used by an earlier location; "
                                            "rename one")
        self.placements[name] = placement
        self.boxes[name] = shape

    def _object(self, index: int, entry: Any) -> dict[str, Any] | None:
        at: tuple[str | int, ...] = ("objects", index)
        entry = self._mapping(("objects", index), entry, "a category and a parent")
        if not entry.get("category"):
            raise self.fail(at, "an object is a mapping with a category and a parent")
        category = self._sayable(entry["category"], (*at, "category"))
        written = _first_choice(entry.get("parent"))
        if written is None:
            written = next(iter(self.placements), None)
            if written is None:
                raise self.fail(at, "has no parent and the world has no location to put it on")
            self.warn(at, f"has no parent (pyrobosim picks one at random); it lies on "
                          f"'{written}'")
        elif not isinstance(entry.get("parent"), str):
            self.warn((*at, "parent"), f"pyrobosim picks its parent at random; homebot puts "
                                        f"it on '{written}' (the first, or most probable)")
        if _name(str(written)) in self.dropped:
            self.warn(at, f"its parent '{written}' was left out, so it is too")
            return None
        placement = self._resolve_parent(str(written), (*at, "parent"))
        name = _unique(self._sayable(entry.get("name") or category, (*at, "name")),
                       {*self.placements, *self.rooms, *self.corridors, *self.object_names})
        self.object_names.add(name)
        self.labels[("objects", index)] = name
        obj: dict[str, Any] = {"name": name, "category": category, "placement": placement}
        if entry.get("pose") is not None:
            pose = self._pose(entry["pose"], (*at, "pose"))
            self.poses[name] = pose
            if self.boxes[placement].covers(Point(pose.x, pose.y)):
                obj["position"] = [round(pose.x, 3), round(pose.y, 3)]
        return obj

    def _resolve_parent(self, written: str, at: tuple[str | int, ...]) -> str:
        """The placement ``written`` (the field at ``at``) names: a location by name, an
        object spawn (``counter0_left``), a location category, or a room and category
        (``kitchen table``), as pyrobosim's ``query_to_entity`` reads them."""
        name = _name(written)
        if name in self.located:
            return self.located[name]
        if name in self.spawns:
            return self.spawns[name]
        words = written.split()
        category = words[-1]
        rooms = [_name(word) for word in words[:-1]]
        candidates = [placement for placement in self.by_category.get(category, [])
                      if all(self.placements[placement]["room"] == room for room in rooms)]
        if candidates:
            if len(self.by_category[category]) > 1:
                self.warn(at, f"'{written}' is a category; pyrobosim picks one at random, "
                              f"homebot the first ('{candidates[0]}')")
            return candidates[0]
        raise self.fail(at, f"parent '{written}' is not a location; locations: "
                            f"{', '.join(self.placements) or 'none'}")

    # ------------------------------------------------------------ the robot and operator

    def _robot(self) -> tuple[float, PlanarPose]:
        robots = self._entries("robots")
        for index, entry in enumerate(robots):
            self._mapping(("robots", index), entry, "a name, a radius and a pose or location")
        if len(robots) > 1:
            self.warn(("robots", 1), f"only the first of {len(robots)} robots is imported; "
                                     "homebot runs one robot")
        first: Mapping[str, Any] = robots[0] if robots else {}
        at: tuple[str | int, ...] = ("robots", 0)
        radius = first.get("radius", 0.25)
        if not is_number(radius) or not 0.05 < radius <= 1.0:
            self.warn((*at, "radius"), f"radius {radius!r} is outside homebot's 0.05-1 m; "
                                        "0.25 m is used")
            radius = 0.25
        target, room = self._robot_target(first, at)
        area = self._free_area(room, float(radius), float(radius) + 0.05)
        point = free_point(area, (target.x, target.y))
        if point is None:
            raise self.fail(at, f"there is no free place for the robot in room '{room}'")
        if math.dist(point, (target.x, target.y)) > 0.01:
            self.warn(at, f"({target.x:.2f}, {target.y:.2f}) is too near a wall or furniture "
                          f"for homebot's robot; it starts at ({point[0]:.2f}, {point[1]:.2f})")
        return float(radius), PlanarPose(point[0], point[1], target.yaw)

    def _robot_target(self, first: Mapping[str, Any],
                      at: tuple[str | int, ...]) -> tuple[PlanarPose, str]:
        """Where the robot should start, and the room that is in."""
        if first.get("pose") is not None:
            pose = self._pose(first["pose"], (*at, "pose"))
            return pose, self._room_at(pose.x, pose.y, at)
        location = _first_choice(first.get("location"))
        if location is not None and not isinstance(first.get("location"), str):
            self.warn((*at, "location"), f"pyrobosim picks the robot's location at random; "
                                          f"homebot starts it at '{location}'")
        if location is None:
            room = next(iter(self.rooms))
            self.warn(at, f"has neither pose nor location; it starts in room '{room}'")
            return self.start_poses.get(room, self.poses[room]), room
        name = _name(str(location))
        if name in self.rooms:
            return self.start_poses.get(name, self.poses[name]), name
        placement = self._resolve_parent(str(location), (*at, "location"))
        cx, cy = self.placements[placement]["center"]
        return PlanarPose(cx, cy), self.placements[placement]["room"]

    def _room_at(self, x: float, y: float, at: tuple[str | int, ...]) -> str:
        for name, shape in {**self.rooms, **self.corridors}.items():
            if shape.covers(Point(x, y)):
                return name
        raise self.fail((*at, "pose"), f"({x:g}, {y:g}) lies in no room or hallway")

    def _free_area(self, room: str, radius: float, clearance: float) -> BaseGeometry:
        shape = {**self.rooms, **self.corridors}[room]
        area: BaseGeometry = shape.buffer(-(_WALL / 2 + radius + 0.03))
        furniture = [box for name, box in self.boxes.items()
                     if self.placements[name]["room"] == room]
        if furniture:
            area = area.difference(unary_union(furniture).buffer(clearance))
        # someone standing in a doorway shuts it, as the occupancy grid sees it
        doorways = [Point(door["position"]).buffer(door["width"] / 2 + radius + 0.1)
                    for door in self.doors if room in door["rooms"]]
        return area.difference(unary_union(doorways)) if doorways else area

    def _operator_place(self, robot: PlanarPose, radius: float) -> dict[str, Any]:
        """The operator, 0.9 m to the robot's left (else anywhere free nearest that)."""
        room = self._room_at(robot.x, robot.y, ("robots", 0))
        wanted = (robot.x + 0.9 * math.cos(robot.yaw + math.pi / 2),
                  robot.y + 0.9 * math.sin(robot.yaw + math.pi / 2))
        for name in [room, *sorted({**self.rooms, **self.corridors}, key=lambda other: (
                {**self.rooms, **self.corridors}[other].distance(Point(robot.x, robot.y))))]:
            area = self._free_area(name, 0.3, 0.35).difference(
                Point(robot.x, robot.y).buffer(radius + 0.45))
            point = free_point(area, wanted)
            if point is not None:
                return {"name": self.operator, "room": name,
                        "position": [round(point[0], 3), round(point[1], 3)]}
        raise WorldError(f"{self.source}: there is no free place for the operator beside the "
                         "robot; make its room larger")


def _name(text: str) -> str:
    return " ".join(text.replace("_", " ").split())


def _unique(name: str, taken: Any) -> str:
    unique, number = name, 2
    while unique in taken:
        unique, number = f"{name} {number}", number + 1
    return unique


def _plural(category: str) -> str:
    if category.endswith(("s", "x", "ch", "sh")):
        return f"{category}es"
    if category.endswith("y") and category[-2:-1] not in set("aeiou"):
        return f"{category[:-1]}ies"
    return f"{category}s"


def _is_round(polygon: Polygon) -> bool:
    """A circle's footprint: turning it changes nothing."""
    return len(polygon.exterior.coords) > 16


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


def _polygons(shape: BaseGeometry) -> list[Polygon]:
    return [shape] if isinstance(shape, Polygon) else [
        part for part in getattr(shape, "geoms", []) if isinstance(part, Polygon)]


def _corners(polygon: Polygon) -> list[list[float]]:
    return [[round(x, 3), round(y, 3)] for x, y in list(polygon.exterior.coords)[:-1]]

