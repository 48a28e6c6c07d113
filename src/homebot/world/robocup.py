"""A playable world built from a RoboCup@Home data directory (names, rooms, locations, objects)."""

from __future__ import annotations

import math
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from homebot.errors import WorldError
from homebot.world.catalogue import CATEGORY_DEFAULTS, defaults_for
from homebot.world.masses import known_mass
from homebot.world.robocup_locations import assign_rooms, furniture_kind, room_table
from homebot.world.robocup_tables import clean_name, read_robocup_data

__all__ = ["RobocupImport", "import_robocup", "read_robocup_data", "room_table",
           "world_from_robocup"]

_CELL = 2.0  # metres between placement centres
_STRIP = 2.5  # free strip along the bottom of every room (doors, people, robot)
_MARGIN = 1.5  # free band along the left wall (doors to the room above)
_FOOTPRINT = (0.8, 0.6)
_SPOTS = frozenset({"entrance", "exit"})
_GESTURES = ("waving", "none", "raising_left_arm", "pointing_right", "raising_right_arm",
             "pointing_left", "none")
_POSTURES = ("standing", "sitting", "standing", "lying", "standing")
_CLOTHES = ("blue t-shirt", "red sweater", "black jacket", "white shirt", "yellow coat",
            "gray sweater", "orange jacket", "blue blouse", "green coat", "black t-shirt")


@dataclass
class RobocupImport:
    """A world built from RoboCup@Home data, and what was skipped on the way."""

    data: dict[str, Any]  #: plain world data, for ``World.from_dict``
    warnings: list[str] = field(default_factory=list)  #: one line per skipped row
    #: (list, index) of the world data -> the input file and line it was built from
    origins: dict[tuple[str, int], str] = field(default_factory=dict)

    def origin(self, location: Sequence[str | int]) -> str | None:
        """The input file and line an entry of ``data`` came from (``World.from_dict``'s
        ``origin``): ``"…/maps/location_names.md: line 7"``; None for what the importer
        made up (doors, the robot without an entrance)."""
        if len(location) > 1 and isinstance(location[1], int):
            return self.origins.get((str(location[0]), location[1]))
        if location and location[0] in ("robot", "operator"):
            return self.origins.get((str(location[0]), 0))
        return None


def world_from_robocup(directory: str | Path, name: str | None = None,
                       rooms_file: str | Path | None = None) -> dict[str, Any]:
    """Plain world data (for ``World.from_dict``) from a RoboCup@Home data directory."""
    return import_robocup(directory, name=name, rooms_file=rooms_file).data


def import_robocup(directory: str | Path, *, name: str | None = None,
                   rooms_file: str | Path | None = None) -> RobocupImport:
    """A world from a RoboCup@Home data directory, with the rows it skipped.

    Rooms are laid out on a grid with doors between neighbours; every location is
    furniture (or a spot, for entrance and exit) in the room the common-sense table
    (``room_table``) gives it; every object lies on a placeable location, its
    category's default location when there is one. The robot starts at the
    entrance, and the first person named is the operator, standing beside it.
    """
    warnings: list[str] = []
    data = read_robocup_data(directory, warnings)
    rooms: list[str] = [clean_name(room) for room in data["rooms"]]
    locations: list[dict[str, Any]] = data["locations"]
    classes: list[dict[str, Any]] = data["classes"]
    _check_clashes(rooms, locations)
    in_room = assign_rooms([location["name"] for location in locations],
                           data["lines"]["locations"], rooms, room_table(rooms_file), warnings)
    per_room = max(1, max(list(in_room.values()).count(room) for room in rooms))
    columns_inside = max(2, math.ceil(math.sqrt(per_room)))
    rows_inside = max(1, math.ceil(per_room / columns_inside))
    width = _MARGIN + columns_inside * _CELL + 0.5
    height = _STRIP + rows_inside * _CELL + 0.5
    grid_columns = math.ceil(math.sqrt(len(rooms)))
    origins = {room: ((index % grid_columns) * width, (index // grid_columns) * height)
               for index, room in enumerate(rooms)}
    category_names = {entry["plural"]: entry["name"] for entry in classes}
    category_names.update({entry["name"]: entry["name"] for entry in classes})
    lines = data["lines"]
    for location, line in zip(locations, lines["locations"], strict=True):
        if location["category"] and location["category"] not in category_names:
            warnings.append(
                f"{line}: location '{location['name']}' names the object category "
                f"'{location['category']}', which objects/objects.md does not list (known: "
                f"{', '.join(sorted(entry['plural'] for entry in classes))}); it holds no "
                "category in the world")
    placements = _placements(locations, in_room, origins, columns_inside, category_names)
    objects = _objects(classes, placements, lines["classes"], warnings)
    people = _people(data["names"], rooms, origins, width)
    start, start_room = _start(placements, origins, rooms, width)
    operator = people[0]
    operator.update(room=start_room, position=[start[0], round(start[1] - 0.9, 2)],
                    posture="standing", gesture="none")
    world = {
        "name": name or clean_name(Path(directory).name) or "robocup",
        "description": f"Built from the RoboCup@Home data in {Path(directory).name}.",
        "rooms": [{"name": room, "polygon": _rectangle(origins[room], width, height)}
                  for room in rooms],
        "doors": _doors(rooms, origins, width, height, grid_columns),
        "placements": placements,
        "categories": [{"name": entry["name"], "plural": entry["plural"]} for entry in classes],
        "objects": objects,
        "people": people,
        "operator": operator["name"],
        "robot": {"pose": [start[0], start[1], 1.5708]},
    }
    return RobocupImport(world, warnings, _origins(lines, placements))


def _origins(lines: Mapping[str, Any],
             placements: list[dict[str, Any]]) -> dict[tuple[str, int], str]:
    """Where each entry of the generated world was read: rooms, placements (one per
    location), categories and objects (in class order), people and the operator (the first
    name), and the robot (at the entrance's row)."""
    origins: dict[tuple[str, int], str] = {}
    for kind, found in (("rooms", lines["rooms"]), ("placements", lines["locations"]),
                        ("people", lines["names"]),
                        ("categories", [entry["class"] for entry in lines["classes"]]),
                        ("objects", [line for entry in lines["classes"]
                                     for line in entry["objects"]])):
        origins.update(((kind, index), line) for index, line in enumerate(found))
    if lines["names"]:
        origins[("operator", 0)] = lines["names"][0]
    entrance = next((index for index, placement in enumerate(placements)
                     if placement["name"].lower() == "entrance"), None)
    if entrance is not None:
        origins[("robot", 0)] = lines["locations"][entrance]
    return origins


def _start(placements: list[dict[str, Any]], origins: dict[str, tuple[float, float]],
           rooms: list[str], width: float) -> tuple[tuple[float, float], str]:
    """Where the robot starts: the entrance spot, else the first room's free strip."""
    entrance = next((p for p in placements if p["name"].lower() == "entrance"), None)
    if entrance is not None:
        return (float(entrance["center"][0]), float(entrance["center"][1])), entrance["room"]
    x0, y0 = origins[rooms[0]]
    return (round(x0 + width - 1.0, 2), round(y0 + 1.9, 2)), rooms[0]


def _check_clashes(rooms: list[str], locations: list[dict[str, Any]]) -> None:
    clashes = sorted({location["name"] for location in locations} & set(rooms))
    if clashes:
        raise WorldError(f"'{clashes[0]}' is both a room and a location; rename one in the "
                         "data directory")


# ---------------------------------------------------------------- layout


def _rectangle(origin: tuple[float, float], width: float, height: float) -> list[list[float]]:
    x, y = origin
    return [[round(x, 3), round(y, 3)], [round(x + width, 3), round(y, 3)],
            [round(x + width, 3), round(y + height, 3)], [round(x, 3), round(y + height, 3)]]


def _doors(rooms: list[str], origins: dict[str, tuple[float, float]], width: float,
           height: float, columns: int) -> list[dict[str, Any]]:
    doors = []
    for index, room in enumerate(rooms):
        x, y = origins[room]
        right = index + 1
        if right < len(rooms) and right % columns != 0:
            doors.append({"name": f"{room} {rooms[right]} door", "rooms": [room, rooms[right]],
                          "position": [round(x + width, 3), round(y + _STRIP / 2, 3)]})
        above = index + columns
        if above < len(rooms):
            doors.append({"name": f"{room} {rooms[above]} door", "rooms": [room, rooms[above]],
                          "position": [round(x + _MARGIN / 2, 3), round(y + height, 3)]})
    return doors


def _placements(locations: list[dict[str, Any]], in_room: dict[str, str],
                origins: dict[str, tuple[float, float]], columns: int,
                category_names: dict[str, str]) -> list[dict[str, Any]]:
    placements = []
    slots: dict[str, int] = {}
    for location in locations:
        room = in_room[location["name"]]
        slot = slots.get(room, 0)
        slots[room] = slot + 1
        x0, y0 = origins[room]
        center = [round(x0 + _MARGIN + _CELL / 2 + (slot % columns) * _CELL, 3),
                  round(y0 + _STRIP + _CELL / 2 + (slot // columns) * _CELL, 3)]
        entry: dict[str, Any] = {
            "name": location["name"], "room": room, "center": center,
            "category": furniture_kind(location["name"], location["placeable"])}
        if location["name"].lower() in _SPOTS:
            entry["kind"] = "spot"
        else:
            entry["size"] = list(_FOOTPRINT)
        category = category_names.get(location["category"] or "")
        if category:
            entry["holds"] = [category]
        placements.append(entry)
    return placements


def _objects(classes: list[dict[str, Any]], placements: list[dict[str, Any]],
             lines: list[dict[str, Any]], warnings: list[str]) -> list[dict[str, Any]]:
    """Every object on its category's placement, else spread over the placeable ones,
    with its typical mass from ``data/robocup/masses.yaml``, else its category's default
    (with a warning naming it)."""
    placeable = [p["name"] for p in placements if p.get("kind") != "spot"]
    objects = []
    spread = 0
    for entry, where in zip(classes, lines, strict=True):
        homes = [p["name"] for p in placements if entry["name"] in p.get("holds", [])]
        for object_name, line in zip(entry["objects"], where["objects"], strict=True):
            if homes:
                placement = homes[0]
            else:
                placement = placeable[spread % len(placeable)]
                spread += 1
            checksum = zlib.crc32(object_name.encode("utf-8"))
            objects.append({"name": object_name, "category": entry["name"],
                            "placement": placement,
                            "size": round(0.05 + (checksum % 30) / 100, 2),
                            "weight": _mass(object_name, entry["name"], line, warnings)})
    return objects


def _mass(name: str, category: str, line: str, warnings: list[str]) -> float:
    known = known_mass(name)
    if known is not None:
        return known.mass
    defaults = defaults_for(category)
    default = defaults.mass
    described = category if any(defaults is found for found in CATEGORY_DEFAULTS.values()) \
        else "an undescribed category"
    warnings.append(f"{line}: no typical mass known for the object '{name}' "
                    "(src/homebot/data/robocup/masses.yaml); took the category default, "
                    f"{default:g} kg ({described})")
    return default


def _people(names: list[str], rooms: list[str], origins: dict[str, tuple[float, float]],
            width: float) -> list[dict[str, Any]]:
    people = []
    for index, person in enumerate(names):
        room = rooms[index % len(rooms)]
        x0, y0 = origins[room]
        slot = index // len(rooms)
        people.append({
            "name": clean_name(person), "room": room,
            "position": [round(x0 + _MARGIN + 0.6 + slot * 1.0, 2), round(y0 + 1.2, 2)],
            "posture": _POSTURES[index % len(_POSTURES)],
            "gesture": _GESTURES[index % len(_GESTURES)],
            "clothes": [_CLOTHES[index % len(_CLOTHES)]],
        })
        if x0 + _MARGIN + 0.6 + slot * 1.0 > x0 + width - 0.5:
            raise WorldError(f"too many people for room '{room}'; the data lists {len(names)}")
    return people
