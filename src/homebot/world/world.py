"""``World``: a validated home with geometry, lookups and cross-reference checks."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from shapely.geometry import LineString, Point, Polygon, box
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union
from shapely.prepared import prep

from homebot.errors import WorldError
from homebot.geometry import Pose
from homebot.text import closest_names, fold, problem_listing
from homebot.world.loading import Origin, locate, validate_document
from homebot.world.model import (
    DisturbanceModel,
    DoorModel,
    PersonModel,
    PlacementKind,
    PlacementModel,
    Posture,
    RobotModel,
    RoomModel,
    WorldModel,
)
from homebot.world.physical import (
    TOLERANCE,
    length_text,
    overlapping_pairs,
    points_inside,
    reach_beyond,
)
from homebot.world.shipped import world_file
from homebot.yamlfile import LocatedDocument, load_yaml_document, parse_yaml_text

__all__ = ["Placement", "World"]

# Clearance between the robot's body and furniture when the approach pose is derived.
_APPROACH_CLEARANCE = 0.12
# The largest occupancy grid a world may ask for (a 150 m square at 5 cm; a few hundred MB).
_MAX_GRID_CELLS = 9e6
_LEAF_THICKNESS = 0.04  #: metres, a door's leaf
#: metres two rooms may reach into each other and still count as touching (coordinates
#: rounded to the millimetre, as importers write them, cross a shared wall by a hair)
_ROOM_OVERLAP_TOLERANCE = 0.001
#: the compass names a door's hinge is given by, as unit vectors on the map
_COMPASS = {"east": (1.0, 0.0), "west": (-1.0, 0.0), "north": (0.0, 1.0), "south": (0.0, -1.0)}


@dataclass(frozen=True, slots=True)
class Placement:
    """A placement with its footprint and the pose the robot uses it from."""

    model: PlacementModel
    footprint: Polygon
    approach: Pose

    @property
    def name(self) -> str:
        return self.model.name

    @property
    def room(self) -> str:
        return self.model.room

    @property
    def category(self) -> str:
        return self.model.category

    @property
    def holds(self) -> list[str]:
        return self.model.holds


#: the lists of entities a command names, with what one entry is called, in file order
_NAMED_KINDS = (("rooms", "room"), ("placements", "placement"), ("doors", "door"),
                ("people", "person"), ("objects", "object"), ("categories", "object category"))
_KIND_OF = dict(_NAMED_KINDS)
#: lists whose entries may share a name: an object named after its category ("apple", an
#: apple) means the same thing either way
_MAY_SHARE_A_NAME = {frozenset(("objects", "categories"))}

#: points whose room ``World.room_at`` remembers (then it starts again)
_ROOM_AT_CACHE = 65_536


class World:
    """The home: rooms, doors, placements, objects, people and the robot.

    A ``World`` is immutable ground truth as loaded; the simulator copies what
    changes (object locations, door states, people) into its own state.
    """

    def __init__(self, model: WorldModel, document: LocatedDocument | None = None,
                 origin: Origin | None = None) -> None:
        self.model = model
        self.source = document.source if document else f"<world {model.name}>"
        self._document = document
        self._origin = origin  # an imported world's errors name the lines of its input
        self._problems: list[str] = []
        #: what is odd but allowed (an object on a placement not meant for its category),
        #: located like errors; ``world check`` prints them
        self.warnings: list[str] = []
        self._wall_lines: BaseGeometry | None = None
        self.rooms = {room.name: room for room in model.rooms}
        self.room_polygons = {room.name: Polygon(room.polygon) for room in model.rooms}
        # room_at answers by point, remembered: the same points (approach poses, people,
        # the points around them) are asked again in every task. Rooms never change.
        self._room_at: dict[tuple[float, float], str | None] = {}
        self.doors = {door.name: door for door in model.doors}
        self.categories = {category.name: category for category in model.categories}
        self.objects = {obj.name: obj for obj in model.objects}
        self.people = {person.name: person for person in model.people}
        self._check_names()
        self._check_rooms()
        self._check_doors()
        self.placements = self._build_placements()
        self._check_overlaps()
        self._check_objects()
        self._check_people()
        self._check_robot()
        if self._problems:
            raise WorldError(problem_listing(self._problems))
        self._check_holdings()
        self._check_swings()

    # ------------------------------------------------------------------ loading

    @classmethod
    def load(cls, path_or_name: str | Path) -> World:
        """Load a world file, or a shipped world by name (``apartment``)."""
        document = load_yaml_document(world_file(path_or_name), WorldError)
        return cls(validate_document(document, WorldModel), document)

    @classmethod
    def from_yaml_text(cls, text: str, source: str = "<text>") -> World:
        """Load a world from YAML text (``source`` names it in errors)."""
        document = parse_yaml_text(text, source, WorldError)
        return cls(validate_document(document, WorldModel), document)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "<dict>", *,
                  origin: Origin | None = None) -> World:
        """Build a world from plain data (as written by ``to_dict``).

        ``origin`` tells, for data an importer generated, which input file and line each
        entry came from; errors then name those lines, not the generated YAML's.
        """
        document = parse_yaml_text(yaml.safe_dump(dict(data), sort_keys=False), source,
                                   WorldError)
        return cls(validate_document(document, WorldModel, origin), document, origin)

    def to_dict(self) -> dict[str, Any]:
        """Plain data that ``from_dict`` reads back to an equal world."""
        data: dict[str, Any] = self.model.model_dump(mode="json", exclude_defaults=True)
        data["name"] = self.model.name
        data["robot"] = self.model.robot.model_dump(mode="json")
        return data

    def save(self, path: str | Path) -> None:
        """Write the world as YAML."""
        Path(path).write_text(yaml.safe_dump(self.to_dict(), sort_keys=False, allow_unicode=True),
                              encoding="utf-8")

    # ------------------------------------------------------------------ lookups

    @property
    def name(self) -> str:
        return self.model.name

    @property
    def robot(self) -> RobotModel:
        return self.model.robot

    @property
    def disturbances(self) -> DisturbanceModel:
        return self.model.disturbances

    @property
    def operator(self) -> PersonModel | None:
        return self.people.get(self.model.operator) if self.model.operator else None

    def forget_cached(self) -> None:
        """Forget what ``room_at`` remembers (for benchmarks that time a truly cold start)."""
        self._room_at.clear()

    def room_at(self, x: float, y: float) -> str | None:
        """The room containing the point, or None when it is outside every room."""
        key = (x, y)
        cache = self._room_at
        if key in cache:
            return cache[key]
        point = Point(x, y)
        found = None
        for name, polygon in self.room_polygons.items():
            if polygon.covers(point):
                found = name
                break
        if len(cache) >= _ROOM_AT_CACHE:
            cache.clear()
        cache[key] = found
        return found

    def placement(self, name: str) -> Placement:
        """The named placement; an unknown name raises ``WorldError`` with a suggestion."""
        if name in self.placements:
            return self.placements[name]
        raise WorldError(_unknown("placement", name, self.placements))

    def room(self, name: str) -> RoomModel:
        """The named room; an unknown name raises ``WorldError`` with a suggestion."""
        if name in self.rooms:
            return self.rooms[name]
        raise WorldError(_unknown("room", name, self.rooms))

    def person(self, name: str) -> PersonModel:
        """The named person; an unknown name raises ``WorldError`` with a suggestion."""
        if name in self.people:
            return self.people[name]
        raise WorldError(_unknown("person", name, self.people))

    def point_before_door(self, door: str, room: str,
                          distance: float) -> Pose:
        """A point ``distance`` metres into ``room`` straight in front of ``door``, facing it.

        "Straight in front" is along the normal of the room's wall at the door, so
        the point stays clear of the wall even in a long, narrow room.
        """
        x, y = self.doors[door].position
        polygon = self.room_polygons[room]
        boundary = polygon.exterior
        along = boundary.project(Point(x, y))
        before = boundary.interpolate(max(along - 0.05, 0.0))
        after = boundary.interpolate(min(along + 0.05, boundary.length))
        tx, ty = after.x - before.x, after.y - before.y
        norm = math.hypot(tx, ty) or 1.0
        nx, ny = -ty / norm, tx / norm
        if not polygon.covers(Point(x + 0.1 * nx, y + 0.1 * ny)):
            nx, ny = -nx, -ny
        return Pose(x + nx * distance, y + ny * distance, math.atan2(-ny, -nx))

    def door_normal(self, door: str, room: str | None = None) -> tuple[float, float]:
        """The unit vector across ``door``'s wall pointing into ``room`` (default the
        first of the door's rooms), as ``point_before_door`` steps along it."""
        model = self.doors[door]
        into = self.point_before_door(door, room or model.rooms[0], 1.0)
        return into.x - model.position[0], into.y - model.position[1]

    def plural_of(self, category: str) -> str:
        """The plural of an object category (its declared plural, else ``category + s``)."""
        declared = self.categories.get(category)
        return declared.plural if declared else f"{category}s"

    def placements_in(self, room: str) -> list[Placement]:
        """Placements of a room, in file order."""
        return [placement for placement in self.placements.values() if placement.room == room]

    def placements_holding(self, category: str) -> list[Placement]:
        """Placements meant to hold objects of ``category``, in file order."""
        return [p for p in self.placements.values() if category in p.holds]

    def bounds(self) -> tuple[float, float, float, float]:
        """(min x, min y, max x, max y) over all rooms."""
        xs = [x for polygon in self.room_polygons.values() for x in polygon.exterior.xy[0]]
        ys = [y for polygon in self.room_polygons.values() for y in polygon.exterior.xy[1]]
        return min(xs), min(ys), max(xs), max(ys)

    # ------------------------------------------------------------------ checks

    def _problem(self, location: list[str | int], message: str) -> None:
        if self._document is not None:
            self._problems.append(locate(self._document, location, message, self._origin))
        else:
            where = ".".join(str(step) for step in location)
            self._problems.append(f"{self.source}: {where}: {message}")

    def _check_names(self) -> None:
        groups: list[tuple[str, Iterable[Any]]] = [
            ("rooms", self.model.rooms), ("doors", self.model.doors),
            ("placements", self.model.placements), ("categories", self.model.categories),
            ("objects", self.model.objects), ("people", self.model.people),
        ]
        for field, entries in groups:
            seen: dict[str, str] = {}  # folded -> as written: "José" and "jose" are one name
            for index, entry in enumerate(entries):
                earlier = seen.get(fold(entry.name))
                if earlier is None:
                    seen[fold(entry.name)] = entry.name
                elif earlier == entry.name:
                    self._problem([field, index, "name"],
                                  f"'{entry.name}' is used twice in {field}; rename one")
                else:
                    self._problem([field, index, "name"],
                                  f"'{entry.name}' and '{earlier}' in {field} differ only in "
                                  "accents or case, and people say them alike; rename one")
        self._check_shared_names()

    def _check_shared_names(self) -> None:
        """A name used by two kinds of entity ("go to the hall": the room or the person?)."""
        first: dict[str, tuple[str, int, str]] = {}  # folded -> (field, index, as written)
        for field, kind in _NAMED_KINDS:
            for index, entry in enumerate(getattr(self.model, field)):
                earlier = first.setdefault(fold(entry.name), (field, index, entry.name))
                if earlier[0] == field or frozenset((field, earlier[0])) in _MAY_SHARE_A_NAME:
                    continue  # names used twice in one list are _check_names's
                other_field, other_index, other_name = earlier
                same = "" if other_name == entry.name else \
                    f" ('{other_name}', but for accents or case)"
                self._problem([field, index, "name"],
                              f"'{entry.name}' is also a {_KIND_OF[other_field]} name{same} "
                              f"({self._where(other_field, other_index)}), so a command "
                              f"naming it could mean either; rename the {kind}")

    def _check_rooms(self) -> None:
        for index, room in enumerate(self.model.rooms):
            polygon = self.room_polygons[room.name]
            if not polygon.is_valid or polygon.area <= 0:
                self._problem(["rooms", index, "polygon"],
                              "polygon is not a simple area; list its corners in order")
        if self._problems:  # geometry on broken polygons fails; every later check would too
            raise WorldError(problem_listing(self._problems))
        names = list(self.room_polygons)
        cores = {name: polygon.buffer(-_ROOM_OVERLAP_TOLERANCE, join_style="mitre")
                 for name, polygon in self.room_polygons.items()}
        for i, first in enumerate(names):
            for second in names[i + 1:]:
                if cores[first].intersection(self.room_polygons[second]).area > 1e-6:
                    overlap = self.room_polygons[first].intersection(
                        self.room_polygons[second]).area
                    amount = (f"{overlap:.2f} m²" if overlap >= 0.01
                              else f"{overlap * 1e4:.0f} cm²")
                    self._problem(["rooms", i, "polygon"],
                                  f"room '{first}' overlaps room '{second}' by {amount}")
        min_x, min_y, max_x, max_y = self.bounds()
        resolution = self.model.grid_resolution
        cells = (max_x - min_x) / resolution * ((max_y - min_y) / resolution)
        if cells > _MAX_GRID_CELLS:
            self._problem(["grid_resolution"],
                          f"the rooms span {max_x - min_x:g} × {max_y - min_y:g} m, "
                          f"{cells:.3g} grid cells at {resolution:g} m (at most "
                          f"{_MAX_GRID_CELLS:.0e}); use a coarser grid_resolution or smaller rooms")
            raise WorldError("\n".join(self._problems))  # no geometry on rooms of that size

    def _check_doors(self) -> None:
        tolerance = self.model.wall_thickness + 0.05
        for index, door in enumerate(self.model.doors):
            self._check_door(index, door, tolerance)

    def _check_door(self, index: int, door: DoorModel, tolerance: float) -> None:
        unknown = [room for room in door.rooms if room not in self.rooms]
        for room in unknown:
            self._problem(["doors", index, "rooms"], _unknown("room", room, self.rooms))
        if unknown:
            return
        if door.rooms[0] == door.rooms[1]:
            self._problem(["doors", index, "rooms"], "a door must join two different rooms")
            return
        point = Point(door.position)
        off_the_wall = [room for room in door.rooms
                        if self.room_polygons[room].exterior.distance(point) > tolerance]
        for room in off_the_wall:
            self._problem(["doors", index, "position"],
                          f"{list(door.position)} is not on the wall of room '{room}'; "
                          "put the door on the wall the two rooms share")
        if off_the_wall:
            return
        if door.swings_into is not None and door.swings_into not in door.rooms:
            self._problem(["doors", index, "swings_into"],
                          f"'{door.swings_into}' is not one of the door's rooms; use "
                          f"'{door.rooms[0]}' or '{door.rooms[1]}'")
        if door.hinge is not None:
            along = _wall_direction(self.room_polygons[door.rooms[0]], door.position)
            if abs(_COMPASS[door.hinge][0] * along[0] + _COMPASS[door.hinge][1] * along[1]) < 0.5:
                ends = " or ".join(name for name, (cx, cy) in _COMPASS.items()
                                   if abs(cx * along[0] + cy * along[1]) >= 0.5)
                self._problem(["doors", index, "hinge"],
                              f"the hinge is at an end of the doorway along the wall, and "
                              f"'{door.hinge}' points across it; use {ends}")

    def door_hinge_direction(self, door: str) -> tuple[float, float]:
        """The unit vector along the wall from the doorway's middle to the jamb the leaf
        turns on: the world file's ``hinge``, else the west end (the south end of a wall
        running north-south)."""
        model = self.doors[door]
        tx, ty = _wall_direction(self.room_polygons[model.rooms[0]], model.position)
        hinge = _COMPASS[model.hinge] if model.hinge else (
            _COMPASS["west"] if abs(tx) >= abs(ty) else _COMPASS["south"])
        return (-tx, -ty) if hinge[0] * tx + hinge[1] * ty < 0 else (tx, ty)

    def door_leaf(self, door: str) -> BaseGeometry | None:
        """Where an open door's leaf stands, 4 cm thick, as the world file's ``opening``,
        ``hinge`` and ``swings_into`` place it; None for a door whose leaf lies flat
        against the wall (no ``opening``)."""
        model = self.doors[door]
        if model.opening is None:
            return None
        (hx, hy), (dx, dy) = self.door_leaf_turned(door, math.radians(model.opening))
        leaf: BaseGeometry = LineString([(hx, hy), (hx + dx * model.width,
                                                     hy + dy * model.width)]).buffer(
            _LEAF_THICKNESS / 2, cap_style="flat")
        return leaf

    def door_leaf_turned(self, door: str, angle: float
                         ) -> tuple[tuple[float, float], tuple[float, float]]:
        """The hinge of ``door``'s leaf and the unit direction the leaf points in when
        turned ``angle`` radians from shut, towards the room it swings into (shut, it
        points from the hinge to the far jamb)."""
        model = self.doors[door]
        cx, cy = model.position
        nx, ny = self.door_normal(door, model.swings_into)
        tx, ty = self.door_hinge_direction(door)
        hinge = (cx + tx * model.width / 2, cy + ty * model.width / 2)
        return hinge, (-tx * math.cos(angle) + nx * math.sin(angle),
                       -ty * math.cos(angle) + ny * math.sin(angle))

    def _build_placements(self) -> dict[str, Placement]:
        footprints = {
            p.name: box(p.center[0] - p.size[0] / 2, p.center[1] - p.size[1] / 2,
                        p.center[0] + p.size[0] / 2, p.center[1] + p.size[1] / 2)
            for p in self.model.placements
        }
        furniture = [footprints[p.name] for p in self.model.placements
                     if p.kind is PlacementKind.FURNITURE]
        placements: dict[str, Placement] = {}
        for index, model in enumerate(self.model.placements):
            if model.room not in self.rooms:
                self._problem(["placements", index, "room"],
                              _unknown("room", model.room, self.rooms))
                continue
            if not self.room_polygons[model.room].covers(Point(model.center)):
                self._problem(["placements", index, "center"],
                              f"{list(model.center)} lies "
                              f"{_outside_by(self.room_polygons[model.room], model.center)} "
                              f"outside room '{model.room}'; move it into the room")
                continue
            beyond = reach_beyond(footprints[model.name], self.room_polygons[model.room])
            if beyond > TOLERANCE:
                width, depth = model.size
                self._problem(["placements", index, "size"],
                              f"the {model.name} ({width:.3g} × {depth:.3g} m around "
                              f"{list(model.center)}) reaches {length_text(beyond)} beyond the "
                              f"walls of room '{model.room}'; give its true size, or move its "
                              "center so that it stands in the room")
                continue
            if self.categories:
                for position, category in enumerate(model.holds):
                    if category not in self.categories:
                        self._problem(["placements", index, "holds", position],
                                      _unknown("object category", category, self.categories))
            if model.approach and not self.room_polygons[model.room].covers(
                    Point(model.approach.xy())):
                self._problem(["placements", index, "approach"],
                              f"{list(model.approach.xy())} lies outside room '{model.room}'; "
                              "the robot stands in the placement's room to use it")
            approach = model.approach or self._derive_approach(model, footprints[model.name],
                                                               furniture)
            if approach is None:
                self._problem(["placements", index],
                              "no free side to approach it from; give an 'approach' pose")
                continue
            placements[model.name] = Placement(model, footprints[model.name], approach)
        return placements

    def _check_overlaps(self) -> None:
        """Furniture stands apart: no piece in another (a table in the counter)."""
        indexed = [(index, self.placements[model.name]) for index, model
                   in enumerate(self.model.placements) if model.name in self.placements
                   and model.kind is PlacementKind.FURNITURE]
        for first, second, depth in overlapping_pairs([p.footprint for _, p in indexed]):
            (earlier, one), (index, other) = indexed[first], indexed[second]
            self._problem(["placements", index, "center"],
                          f"the {other.name} overlaps the {one.name} "
                          f"({self._where('placements', earlier)}) by {length_text(depth)}; "
                          "move one of them, or give their true sizes")

    def _where(self, field: str, index: int) -> str:
        """``placements.3, line 14``: where an entry another message names is written."""
        if self._origin is not None:
            found = self._origin([field, index, "name"])
            return f"{field}.{index}" + (f", {found}" if found else "")
        line = self._document.line_of([field, index, "name"]) if self._document else None
        return f"{field}.{index}" + (f", line {line}" if line is not None else "")

    def _derive_approach(self, model: PlacementModel, footprint: Polygon,
                         furniture: list[Polygon]) -> Pose | None:
        """The nearest free standing point facing the placement, on its most open side."""
        radius = self.model.robot.radius
        if model.kind is PlacementKind.SPOT:
            return Pose(model.center[0], model.center[1], 0.0)
        room = self.room_polygons[model.room]
        free_area = prep(room.buffer(-(radius + self.model.wall_thickness / 2)))
        obstacles = [f.buffer(radius + 0.02) for f in furniture if not f.equals(footprint)]
        cx, cy = model.center
        half_w, half_d = model.size[0] / 2, model.size[1] / 2
        offset = radius + _APPROACH_CLEARANCE
        room_center = room.centroid
        sides = [(cx + half_w + offset, cy), (cx - half_w - offset, cy),
                 (cx, cy + half_d + offset), (cx, cy - half_d - offset)]
        sides.sort(key=lambda xy: math.dist(xy, (room_center.x, room_center.y)))
        for x, y in sides:
            spot = Point(x, y)
            if free_area.contains(spot) and not any(o.contains(spot) for o in obstacles):
                return Pose(round(x, 3), round(y, 3), round(math.atan2(cy - y, cx - x), 4))
        return None

    def _check_objects(self) -> None:
        # a placement written but refused has its own message; its objects add none
        refused = {model.name for model in self.model.placements} - set(self.placements)
        for index, obj in enumerate(self.model.objects):
            if obj.placement not in self.placements:
                if obj.placement not in refused:
                    self._problem(["objects", index, "placement"],
                                  _unknown("placement", obj.placement, self.placements))
            elif obj.position is not None and not (
                    self.placements[obj.placement].footprint.covers(Point(obj.position))):
                self._problem(["objects", index, "position"],
                              f"{list(obj.position)} is not on the surface of "
                              f"'{obj.placement}'; give a point inside its footprint or leave "
                              "the position out")
            if self.categories and obj.category not in self.categories:
                self._problem(["objects", index, "category"],
                              _unknown("object category", obj.category, self.categories))

    def _check_holdings(self) -> None:
        """Warn of an object on a placement whose ``holds`` leaves its category out (a towel
        in the fridge): allowed, since a home has things out of place to tidy, but often a
        slip in the file."""
        for index, obj in enumerate(self.model.objects):
            holds = self.placements[obj.placement].holds
            if holds and fold(obj.category) not in {fold(held) for held in holds}:
                message = (f"the {obj.name} ({obj.category}) is on the {obj.placement}, which "
                           f"holds {', '.join(holds)}: a tidy-up would move it; if it belongs "
                           f"there, add {obj.category} to the {obj.placement}'s holds")
                self._warn(["objects", index, "placement"], message)

    def _check_swings(self) -> None:
        """Warn of a placement whose approach spot a door's leaf sweeps over (``swings``)."""
        from homebot.world.swings import approaches_in_swings

        for index, message in approaches_in_swings(self):
            self._warn(["placements", index, "center"], message)

    def _warn(self, location: list[str | int], message: str) -> None:
        if self._document is not None:
            self.warnings.append(locate(self._document, location, message, self._origin))
        else:
            where = ".".join(str(step) for step in location)
            self.warnings.append(f"{self.source}: {where}: {message}")

    def _check_people(self) -> None:
        for index, person in enumerate(self.model.people):
            if person.room not in self.rooms:
                self._problem(["people", index, "room"], _unknown("room", person.room, self.rooms))
            elif not self.room_polygons[person.room].covers(Point(person.position)):
                self._problem(["people", index, "position"],
                              f"{list(person.position)} lies "
                              f"{_outside_by(self.room_polygons[person.room], person.position)} "
                              f"outside room '{person.room}'; move them into the room")
        self._check_standing_room()
        if self.model.operator is not None and self.model.operator not in self.people:
            self._problem(["operator"], _unknown("person", self.model.operator, self.people))

    def _check_standing_room(self) -> None:
        """A standing person is not inside furniture (sitting or lying, they may be on it)."""
        furniture = [placement for placement in self.placements.values()
                     if placement.model.kind is PlacementKind.FURNITURE]
        standing = [(index, person) for index, person in enumerate(self.model.people)
                    if person.posture is Posture.STANDING and person.room in self.rooms
                    and self.room_polygons[person.room].covers(Point(person.position))]
        for point, footprint, depth in points_inside(
                [placement.footprint for placement in furniture],
                [person.position for _, person in standing]):
            index, person = standing[point]
            self._problem(["people", index, "position"],
                          f"{person.name} stands {length_text(depth)} inside the "
                          f"{furniture[footprint].name}; move them beside it (or give a "
                          "posture, sitting or lying, to have them on it)")

    def footprint_problem(self, x: float, y: float, radius: float | None = None) -> str | None:
        """Why the robot's disc centred at (x, y) does not fit on the floor; None when it fits.

        The centre must lie in a room, and the disc (``radius``, the robot's by
        default) must not overlap furniture or a wall. Walls run along every room
        boundary except door openings and are ``wall_thickness`` thick, as the
        occupancy grid draws them. The message reads after the point, e.g.
        ``"is inside the sofa"``.
        """
        radius = self.model.robot.radius if radius is None else radius
        if self.room_at(x, y) is None:
            nearest = min(self.room_polygons,
                          key=lambda name: self.room_polygons[name].distance(Point(x, y)))
            return (f"is outside every room ({_outside_by(self.room_polygons[nearest], (x, y))} "
                    f"from the nearest, '{nearest}')")
        point = Point(x, y)
        for placement in self.placements.values():
            if placement.model.kind is not PlacementKind.FURNITURE:
                continue
            if placement.footprint.covers(point):
                return f"is inside the {placement.name}"
            gap = placement.footprint.distance(point)
            if gap < radius:
                return (f"is {gap:.2f} m from the {placement.name}, closer than the robot's "
                        f"radius {radius:g} m")
        gap = self._walls().distance(point) - self.model.wall_thickness / 2
        if gap <= 0:
            return "is inside a wall"
        if gap < radius:
            return f"is {gap:.2f} m from a wall, closer than the robot's radius {radius:g} m"
        return None

    def _walls(self) -> BaseGeometry:
        """The walls' centre lines: room boundaries without the door openings."""
        if self._wall_lines is None:
            lines = unary_union([polygon.exterior for polygon in self.room_polygons.values()])
            openings = [Point(door.position).buffer(door.width / 2)
                        for door in self.doors.values()]
            self._wall_lines = lines.difference(unary_union(openings)) if openings else lines
        return self._wall_lines

    def _check_robot(self) -> None:
        x, y = self.model.robot.pose.xy()
        problem = self.footprint_problem(x, y)
        if problem is not None:
            self._problem(["robot", "pose"], f"the robot at ({x:g}, {y:g}) {problem}; place it "
                          "inside a room, at least its radius from walls and furniture")
        arm = self.arm_model_path()
        if arm is not None and (arm.suffix.lower() != ".xml" or not arm.is_file()):
            self._problem(["robot", "arm"], f"{arm} is no MJCF file (.xml) that exists; name "
                          "the arm's model relative to the world file, or leave 'arm' out")

    def arm_model_path(self) -> Path | None:
        """The arm's MJCF file the world names (``robot.arm``, relative to the world file's
        folder), or None for homebot's own."""
        arm = self.model.robot.arm
        if arm is None:
            return None
        path = Path(arm)
        if not path.is_absolute() and self._document is not None:
            path = Path(self.source).parent / path
        return path


def _wall_direction(room: Polygon, point: tuple[float, float]) -> tuple[float, float]:
    """The unit vector along ``room``'s wall at ``point``."""
    boundary = room.exterior
    along = boundary.project(Point(point))
    before = boundary.interpolate(max(along - 0.05, 0.0))
    after = boundary.interpolate(min(along + 0.05, boundary.length))
    tx, ty = after.x - before.x, after.y - before.y
    norm = math.hypot(tx, ty) or 1.0
    return (tx / norm, ty / norm)


def _outside_by(room: Polygon, point: tuple[float, float]) -> str:
    """How far ``point`` lies from ``room``, for a message: ``"2.5 m"``, ``"30 cm"``."""
    return length_text(room.distance(Point(point)))


def _unknown(kind: str, name: str, known: Iterable[str]) -> str:
    names = sorted(known)
    guess = closest_names(name, names)
    hint = f"did you mean '{guess[0]}'?" if guess else f"known: {', '.join(names) or 'none'}"
    return f"unknown {kind} '{name}'; {hint}"
