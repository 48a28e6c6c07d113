"""Which fields of a pyrobosim world file homebot reads, and why it leaves the others.

Each field that is not read is reported once per kind of entry and reason, at the line of
its first use (``rooms[*].color, rooms[*].wall_width: not imported: ...``), so that a
world of fifty rooms gives a handful of warnings rather than a hundred.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

__all__ = ["FIELDS_READ", "UnreadFields"]

_WALL = "homebot's walls are 0.1 m thick, centred on the outline"
_LOOK = "homebot draws the world in its own colours"
_SIMULATOR = "pyrobosim's own simulator settings; homebot's robot and grid have their own"
_UNKNOWN = "not in pyrobosim's world schema (a typo?)"

#: the fields of each section (``""``: the top of the file) that the importer reads
FIELDS_READ: Mapping[str, frozenset[str]] = {
    "": frozenset({"params", "metadata", "robots", "rooms", "hallways", "locations",
                   "objects"}),
    "params": frozenset({"name"}),
    "metadata": frozenset({"locations"}),
    "rooms": frozenset({"name", "footprint", "pose"}),
    "hallways": frozenset({"room_start", "room_end", "width", "conn_method", "conn_angle",
                           "offset", "conn_points", "is_open", "is_locked"}),
    "locations": frozenset({"name", "category", "parent", "pose", "is_open", "is_locked"}),
    "objects": frozenset({"name", "category", "parent", "pose"}),
    "robots": frozenset({"name", "radius", "pose", "location"}),
}
_WHY_NOT_READ: Mapping[str, Mapping[str, str]] = {
    "params": {"inflation_radius": _SIMULATOR, "object_radius": _SIMULATOR,
               "wall_height": "homebot's walls have no height"},
    "metadata": {"objects": "homebot's catalogue gives objects their shape, size and mass"},
    "rooms": {"color": _LOOK, "height": "homebot's rooms have no height", "wall_width": _WALL,
              "nav_poses": "homebot works out where to stand by itself (the first nav pose "
                           "of the robot's start room is its start)"},
    "hallways": {"color": _LOOK, "wall_width": _WALL},
    "locations": {"color": _LOOK, "is_charger": "homebot's robot does not charge",
                  "nav_poses": "homebot works out where to stand by itself"},
    "objects": {"color": _LOOK},
}
# sections holding one mapping, not a list of entries
_SINGLE = frozenset({"", "params", "metadata"})

Location = tuple[str | int, ...]


class UnreadFields:
    """The fields not read, grouped by section and reason, with where each group began."""

    def __init__(self) -> None:
        self._groups: dict[tuple[str, str], tuple[Location, list[str]]] = {}

    def note(self, location: Location, section: str, entry: Mapping[str, Any]) -> None:
        """Remember the fields of ``entry`` (at ``location``) that are not read."""
        for key in map(str, entry):
            if key in FIELDS_READ[section]:
                continue
            reason = _WHY_NOT_READ.get(section, {}).get(key) or (
                _SIMULATOR if section == "robots" else _UNKNOWN)
            _first, keys = self._groups.setdefault((section, reason), ((*location, key), []))
            if key not in keys:
                keys.append(key)

    def report(self) -> list[tuple[Location, str]]:
        """Per group: the location of its first field, and ``"rooms[*].color: not
        imported: <reason>"``."""
        lines = []
        for (section, reason), (location, keys) in self._groups.items():
            prefix = f"{section}." if section in _SINGLE - {""} else (
                f"{section}[*]." if section else "")
            names = ", ".join(f"{prefix}{key}" for key in keys)
            lines.append((location, f"{names}: not imported: {reason}"))
        return lines
