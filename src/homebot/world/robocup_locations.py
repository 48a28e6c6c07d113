"""What a RoboCup@Home location is and which room it stands in, from the words of its name.

Teams name their furniture freely ("dinner table", "trashcan", "hallway cabinet",
"TV stand"), so the importer reads a name by its words rather than matching whole
names against a list: the common-sense table (``data/robocup/rooms.yaml``) maps a
word or a whole name to the rooms it most likely stands in.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from importlib import resources
from pathlib import Path

from homebot.errors import WorldError
from homebot.world.robocup_tables import clean_name
from homebot.yamlfile import LocatedDocument, field_error, load_yaml_document, parse_yaml_text

__all__ = ["FALLBACK", "assign_rooms", "furniture_kind", "room_table"]

#: the table's key for where a location matching nothing goes
FALLBACK = "*"
_SPOTS = frozenset({"entrance", "exit"})
#: furniture kind by a word of the name, the last word (the head noun) asked first
_KINDS = {"table": "table", "desk": "table", "counter": "counter", "countertop": "counter",
          "island": "counter", "sink": "counter", "shelf": "storage", "shelves": "storage",
          "bookshelf": "storage", "bookcase": "storage", "cabinet": "storage",
          "cupboard": "storage", "rack": "storage", "stand": "storage", "dresser": "storage",
          "wardrobe": "storage", "drawer": "storage", "drawers": "storage",
          "sideboard": "storage", "pantry": "storage", "nightstand": "table",
          "bed": "seating", "sofa": "seating", "couch": "seating", "chair": "seating",
          "armchair": "seating", "bench": "seating", "stool": "seating",
          "lamp": "lamp", "bin": "bin", "trashbin": "bin", "basket": "bin", "can": "bin",
          "trashcan": "bin", "fridge": "appliance", "refrigerator": "appliance",
          "freezer": "appliance", "dishwasher": "appliance", "oven": "appliance",
          "stove": "appliance", "microwave": "appliance", "washer": "appliance"}


def room_table(rooms_file: str | Path | None = None) -> dict[str, list[str]]:
    """Location name or word -> likely rooms: ``--rooms FILE``'s entries, then the shipped ones.

    Raises ``WorldError`` when the file cannot be read or is not a mapping of names
    to a room or a list of rooms.
    """
    shipped = resources.files("homebot.data").joinpath("robocup", "rooms.yaml")
    table = _room_entries(parse_yaml_text(shipped.read_text(encoding="utf-8"), "rooms.yaml",
                                          WorldError))
    if rooms_file is None:
        return table
    return {**table, **_room_entries(load_yaml_document(rooms_file, WorldError))}


def _room_entries(document: LocatedDocument) -> dict[str, list[str]]:
    loaded = document.data
    if not isinstance(loaded, Mapping):
        raise WorldError(f"{document.source}: line 1: expected a mapping of 'location: room' "
                         f"lines, got {type(loaded).__name__}")
    table: dict[str, list[str]] = {}
    for key, value in loaded.items():
        rooms = [value] if isinstance(value, str) else value
        if not isinstance(key, str) or not isinstance(rooms, list) or not rooms or not all(
                isinstance(room, str) for room in rooms):
            raise WorldError(field_error(document, [str(key)], "needs a room or a list of "
                                         f"rooms, e.g. '{key}: kitchen'"))
        name = key.strip() if key.strip() == FALLBACK else clean_name(key).lower()
        table[name] = [clean_name(room).lower() for room in rooms]
    return table


def assign_rooms(locations: list[str], lines: list[str], rooms: list[str],
                 table: Mapping[str, list[str]], warnings: list[str]) -> dict[str, str]:
    """Each location's room. Asked in turn, the first answer naming a room of the data wins:

    1. the table, for the location's whole name ("side table"; a plural also as its
       singular);
    2. a room the name itself names ("hallway cabinet": the hallway; "kitchen counter");
    3. the table, for each word of the name from left to right, where the words that
       say where ("desk lamp", "dinner table", "TV stand") come first; a compound word
       also by the word it starts or ends with ("trashcan": trash, "coathanger": coat);
    4. the fallback: the table's ``"*"`` entry (the living room or its like), else the
       room with the fewest locations, with a warning naming the location.

    A table room matches a room of the data named the same, or whose name holds its
    words ("bedroom": "master bedroom"; "living room": "livingroom").
    """
    assigned: dict[str, str] = {}
    counts = dict.fromkeys(rooms, 0)
    unplaced = []
    for location, line in zip(locations, lines, strict=True):
        asked = list(_candidates(location, rooms, table))
        room = next((found for found in (_room_of(candidates, rooms) for candidates in asked)
                     if found is not None), None)
        if room is None:
            unplaced.append((location, line, asked[0] if asked else []))
            continue
        assigned[location] = room
        counts[room] += 1
    fallback = _room_of(table.get(FALLBACK, []), rooms)
    for location, line, wanted in unplaced:
        room = fallback or min(rooms, key=lambda r: (counts[r], rooms.index(r)))
        assigned[location] = room
        counts[room] += 1
        why = (f"the location '{location}' belongs in a {' or '.join(wanted)}, which the "
               "data does not have" if wanted else
               f"no word of the location '{location}' says which room it stands in")
        warnings.append(f"{line}: {why}; put it in the {room} (a --rooms file line "
                        f"'{location.lower()}: ROOM' chooses)")
    return {location: assigned[location] for location in locations}


def _candidates(location: str, rooms: list[str],
                table: Mapping[str, list[str]]) -> Iterator[list[str]]:
    """The room lists to ask, in order (see ``assign_rooms``)."""
    words = location.lower().split()
    whole = " ".join(words)
    for key in (whole, _singular(whole)):
        if key in table:
            yield table[key]
    for room in rooms:
        if _holds_words(words, room.lower().split()):
            yield [room.lower()]
    for word in words:
        for key in (word, _singular(word)):
            if key in table:
                yield table[key]
    for word in words:
        for part in _parts(word, table):
            yield table[part]


def _parts(word: str, table: Mapping[str, list[str]]) -> list[str]:
    """The table's single words a compound word starts or ends with, longest first."""
    keys = [key for key in table if " " not in key and key not in (word, FALLBACK) and (
        (len(key) >= 2 and word.startswith(key)) or (len(key) >= 3 and _singular(
            word).endswith(key)))]
    return sorted(keys, key=lambda key: (not word.startswith(key), -len(key)))


def _room_of(candidates: list[str], rooms: list[str]) -> str | None:
    """The first of ``candidates`` (room kinds) the data has, by name or by words."""
    for candidate in candidates:
        wanted = candidate.split()
        for room in rooms:
            words = room.lower().split()
            if words == wanted or "".join(words) == "".join(wanted) or _holds_words(
                    words, wanted):
                return room
    return None


def _holds_words(words: list[str], part: list[str]) -> bool:
    """Whether ``part`` occurs in ``words`` as consecutive whole words."""
    return any(words[start:start + len(part)] == part
               for start in range(len(words) - len(part) + 1))


def _singular(word: str) -> str:
    return word[:-1] if word.endswith("s") and not word.endswith("ss") else word


def furniture_kind(name: str, placeable: bool) -> str:
    """The furniture category of a location: by its words, the head noun (the last) first
    ("desk lamp": a lamp; "bedside table": a table), a compound word also by its end
    ("bookshelf": storage); a spot for the entrance and exit; else furniture when
    objects can be placed on it, a fixture when not."""
    words = name.lower().split()
    if " ".join(words) in _SPOTS:
        return "spot"
    for word in reversed(words):
        for form in (word, _singular(word)):
            if form in _KINDS:
                return _KINDS[form]
        ending = next((key for key in sorted(_KINDS, key=len, reverse=True)
                       if len(key) >= 3 and _singular(word).endswith(key)), None)
        if ending is not None:
            return _KINDS[ending]
    return "furniture" if placeable else "fixture"
