"""Reading a RoboCup@Home data directory's markdown tables, row by row, with a warning per bad row.

A competition repository holds four tables: ``names/names.md``, ``maps/room_names.md``,
``maps/location_names.md`` (``| Number | Name | Object Category``, ``(p)`` marking where
objects can be placed) and ``objects/objects.md`` (one ``# Class plural (singular)``
heading and an ``| Objectname | Image |`` table per class). Hand-written tables have
slips: a ``|`` missing or one too many, a cell shifted. A row the reader cannot take
as written is skipped with a warning that names its file, line and what is wrong, or,
where only one reading makes sense (``| 3 shelf (p) |``: the number and the name run
together), read that way with a warning that says how.
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from homebot.errors import WorldError
from homebot.files import read_text_file

__all__ = ["clean_name", "read_robocup_data"]

# A cell that stands for no name: "| 4 | - |" in a competition's location table.
_PLACEHOLDER = re.compile(r"[-\u2013\u2014_.?*\s]*|n/?a|tbd|none|todo", re.IGNORECASE)
_PLACEABLE = re.compile(r"\(\s*p\s*\)", re.IGNORECASE)
# "# Class cleaning supplies (cleaning supply)"; the singular may be missing
_CLASS_HEADING = re.compile(r"^#+\s*class\s+(?P<plural>[^(]+?)\s*(?:\((?P<name>[^)]*)\)\s*)?$",
                            re.IGNORECASE)
_IMAGE = re.compile(r"!\[|\]\(|\.(?:png|jpe?g|gif|webp|svg)\b", re.IGNORECASE)


@dataclass(frozen=True, slots=True)
class _Row:
    """One table row: its line number, its text and its cells (trailing empty ones dropped)."""

    number: int
    line: str
    cells: list[str]


class _Notes:
    """The warnings of one file, each with the file and line it concerns."""

    def __init__(self, path: Path, warnings: list[str]) -> None:
        self.path = path
        self.warnings = warnings

    def at(self, number: int) -> str:
        return f"{self.path}: line {number}"

    def skip(self, row: _Row, why: str) -> None:
        self.warnings.append(f"{self.at(row.number)}: skipped the row '{row.line}': {why}")

    def read_as(self, row: _Row, how: str) -> None:
        self.warnings.append(f"{self.at(row.number)}: the row '{row.line}' {how}")


def read_robocup_data(directory: str | Path,
                      warnings: list[str] | None = None) -> dict[str, Any]:
    """The names, rooms, locations (with placeability and category) and object classes.

    Placeholder rows (``| 4 | - |``, as competition repositories hold for locations
    still to be named) and malformed rows are skipped, each with a line in
    ``warnings`` naming the file and line. ``lines`` holds, for each list, the input
    file and line of every entry (``"…/names/names.md: line 4"``; for object classes,
    that of the class's heading and of each object). Raises ``WorldError`` naming the
    missing file or the table it could not read.
    """
    root = Path(directory)
    if not root.is_dir():
        raise WorldError(f"{root}: not a directory; give a RoboCup@Home data directory "
                         "(with names/, maps/ and objects/)")
    skipped = warnings if warnings is not None else []
    names_file, room_names = root / "names" / "names.md", root / "maps" / "room_names.md"
    names, name_lines = _first_column(_read(names_file), _Notes(names_file, skipped))
    rooms, room_lines = _first_column(_read(room_names), _Notes(room_names, skipped))
    locations_file = root / "maps" / "location_names.md"
    location_notes = _Notes(locations_file, skipped)
    locations, location_lines = _locations(_read(locations_file), location_notes)
    objects_file = root / "objects" / "objects.md"
    classes, class_lines = _object_classes(_read(objects_file), _Notes(objects_file, skipped))
    for label, entries, path in (("names", names, names_file), ("rooms", rooms, room_names),
                                 ("locations", locations, locations_file),
                                 ("object classes", classes, objects_file)):
        if not entries:
            raise WorldError(f"{path}: no {label} found; expected a markdown table")
    _split_merged_categories(locations, location_lines, classes, location_notes)
    lines = {"names": name_lines, "rooms": room_lines, "locations": location_lines,
             "classes": class_lines}
    return {"names": names, "rooms": rooms, "locations": locations, "classes": classes,
            "lines": lines}


def clean_name(text: str) -> str:
    """A name as people say it: underscores as spaces, single spaces, no markup; letters of
    any script keep their accents ("Patrícia")."""
    cleaned = re.sub(r"[^\w '\-]|_", " ", unicodedata.normalize("NFC", text))
    return " ".join(cleaned.split()).strip()


# ---------------------------------------------------------------- tables


def _read(path: Path) -> str:
    if not path.exists():
        raise WorldError(f"{path}: no such file; a RoboCup@Home data directory has "
                         "names/names.md, maps/room_names.md, maps/location_names.md "
                         "and objects/objects.md")
    return read_text_file(path, WorldError, "text", "RoboCup@Home data file")


def _cells(line: str) -> list[str]:
    """A table line's cells: one outer ``|`` off each end (``||`` is an empty cell), the
    trailing empty cells dropped (a row may leave its last columns out)."""
    text = line.strip()
    text = text[1:] if text.startswith("|") else text
    text = text[:-1] if text.endswith("|") else text
    cells = [cell.strip() for cell in text.split("|")]
    while cells and not cells[-1]:
        cells.pop()
    return cells


def _table_lines(text: str) -> Iterator[tuple[int, str]]:
    """The table lines of ``text`` (with a ``|``), separator lines (``|---|:---:|``) left out."""
    for number, line in enumerate(text.splitlines(), start=1):
        if "|" in line and not re.fullmatch(r"[\s|:\-]*", line):
            yield number, line.strip()


def _table(text: str) -> tuple[list[str], list[_Row]]:
    """The header's cells and the rows after it."""
    rows = [_Row(number, line, _cells(line)) for number, line in _table_lines(text)]
    if not rows:
        return [], []
    return rows[0].cells, rows[1:]


def _placeholder(cell: str) -> bool:
    return bool(_PLACEHOLDER.fullmatch(_PLACEABLE.sub("", cell).strip()))


def _too_wide(row: _Row, header: list[str], notes: _Notes) -> bool:
    """Whether the row has more cells than the header (an extra ``|``, or two rows run
    together); the row is skipped with a warning."""
    if len(row.cells) <= max(1, len(header)):
        return False
    notes.skip(row, f"it has {len(row.cells)} cells where the header "
                    f"'{' | '.join(header)}' has {len(header)} (a '|' too many?)")
    return True


def _first_column(text: str, notes: _Notes) -> tuple[list[str], list[str]]:
    """The first column's names, and the file and line of each."""
    header, rows = _table(text)
    names, lines = [], []
    for row in rows:
        if not row.cells:
            continue
        if not row.cells[0]:
            notes.skip(row, "its first cell is empty (a cell shifted?)")
        elif _too_wide(row, header, notes):
            continue
        elif _placeholder(row.cells[0]):
            notes.skip(row, "a placeholder, not a name")
        else:
            names.append(row.cells[0])
            lines.append(notes.at(row.number))
    return names, lines


# ---------------------------------------------------------------- locations


def _locations(text: str, notes: _Notes) -> tuple[list[dict[str, Any]], list[str]]:
    """The locations (name, placeable, category), and the file and line of each."""
    header, rows = _table(text)
    # The competition's tables number their rows; a table whose first column is headed
    # as the name ("| Name | Object Category |") does not.
    numbered = not header or not re.search(r"name|location|furniture|place", header[0],
                                           re.IGNORECASE)
    locations, lines = [], []
    for row in rows:
        location = _location(row, header, numbered, notes)
        if location is not None:
            locations.append(location)
            lines.append(notes.at(row.number))
    return locations, lines


def _location(row: _Row, header: list[str], numbered: bool,
              notes: _Notes) -> dict[str, Any] | None:
    """One row's location, or None (with a warning) when the row is skipped."""
    cells = list(row.cells)
    if numbered and cells and cells[0] and not cells[0].isdigit():
        joined = re.fullmatch(r"(\d+)\s*[.):]?\s+(\S.*)", cells[0])
        if joined is None:
            notes.skip(row, f"its first cell '{cells[0]}' is not a number (a cell missing "
                            "or shifted?)")
            return None
        cells[0:1] = [joined.group(1), joined.group(2)]
        notes.read_as(row, f"runs the number and the name together (a '|' missing); "
                           f"read as number {joined.group(1)}, name '{joined.group(2)}'")
    if _too_wide(_Row(row.number, row.line, cells), header, notes):
        return None
    if numbered and len(cells) > 1 and not cells[0]:
        notes.read_as(row, f"has no number; read the location in the name column, "
                           f"'{cells[1]}', all the same")
    name_at = 1 if numbered else 0
    label = cells[name_at] if len(cells) > name_at else ""
    category_cell = cells[name_at + 1] if len(cells) > name_at + 1 else ""
    if not label or _placeholder(label):
        notes.skip(row, "a placeholder, not a location name")
        return None
    marker = _PLACEABLE.search(label)
    placeable = marker is not None
    if marker is not None and label[marker.end():].strip():
        tail = label[marker.end():].strip()
        if category_cell:
            notes.skip(row, f"its name cell '{label}' goes on after '(p)' and the row has "
                            "a category cell too (cells run together?)")
            return None
        label, category_cell = label[:marker.start()], tail
        notes.read_as(row, f"has text after '(p)' (a '|' missing); read as location "
                           f"'{clean_name(label)}', object category '{tail}'")
    if _PLACEABLE.search(category_cell):
        placeable = True
        category_cell = _PLACEABLE.sub("", category_cell).strip()
        notes.read_as(row, "has '(p)' in the category column (a cell shifted); read as "
                           f"the placeable location '{clean_name(label)}'")
    name = clean_name(_PLACEABLE.sub("", label))
    if not name:
        raise WorldError(f"{notes.at(row.number)}: the row '{row.line}' has no location "
                         "name a person could say; write one, or '-' to leave the row out")
    category = clean_name(category_cell).lower() if category_cell and not _placeholder(
        category_cell) else None
    return {"name": name, "placeable": placeable, "category": category or None}


def _split_merged_categories(locations: list[dict[str, Any]], lines: list[str],
                             classes: list[dict[str, Any]], notes: _Notes) -> None:
    """A location without a category whose name ends with a class's plural ("kitchen table
    dishes") lost the ``|`` before its category: read it as name and category, with a
    warning."""
    plurals = sorted((entry["plural"] for entry in classes), key=len, reverse=True)
    for location, line in zip(locations, lines, strict=True):
        if location["category"]:
            continue
        name = location["name"]
        plural = next((p for p in plurals if name.lower().endswith(" " + p)), None)
        if plural is None:
            continue
        location["name"] = name[:-len(plural)].strip()
        location["category"] = plural
        notes.warnings.append(f"{line}: the location '{name}' ends with the object category "
                              f"'{plural}' (a '|' missing?); read as location "
                              f"'{location['name']}', object category '{plural}'")


# ---------------------------------------------------------------- object classes


def _object_classes(text: str,
                    notes: _Notes) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The classes (plural, name, objects), and for each the file and line of its heading
    (``"class"``) and of its objects (``"objects"``)."""
    classes: list[dict[str, Any]] = []
    lines: list[dict[str, Any]] = []
    header: list[str] | None = None  # the current class's table header, once seen
    in_class = False
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("#"):
            heading = _class_heading(stripped, number, notes)
            in_class, header = heading is not None, None
            if heading is not None:
                classes.append(heading)
                lines.append({"class": notes.at(number), "objects": []})
            continue
        if "|" not in stripped or re.fullmatch(r"[\s|:\-]*", stripped):
            continue
        row = _Row(number, stripped, _cells(stripped))
        if not in_class:
            notes.skip(row, "it stands under no '# Class plural (singular)' heading")
        elif header is None:
            header = row.cells
        else:
            found = _object_name(row, header, notes)
            if found:
                classes[-1]["objects"].append(found)
                lines[-1]["objects"].append(notes.at(number))
    if any(not entry["objects"] for entry in classes):
        empty = next(entry["plural"] for entry in classes if not entry["objects"])
        raise WorldError(f"{notes.path}: class '{empty}' lists no objects")
    return classes, lines


def _class_heading(line: str, number: int, notes: _Notes) -> dict[str, Any] | None:
    """The class a ``# Class plural (singular)`` heading opens (words may be separated by
    spaces or underscores), or None for another heading."""
    match = _CLASS_HEADING.match(line)
    if match is None:
        return None
    plural = clean_name(match.group("plural")).lower()
    name = clean_name(match.group("name") or "").lower()
    if not name:
        name = _singular(plural)
        notes.warnings.append(f"{notes.at(number)}: the heading '{line}' gives no singular "
                              f"in brackets ('# Class {plural} (...)'); took '{name}'")
    return {"plural": plural, "name": name, "objects": []}


def _singular(plural: str) -> str:
    words = plural.split()
    last = words[-1]
    if last.endswith("ies") and len(last) > 4:
        last = last[:-3] + "y"
    elif re.search(r"(?:ch|sh|ss|x)es$", last):
        last = last[:-2]
    elif last.endswith("s") and not last.endswith("ss"):
        last = last[:-1]
    return " ".join([*words[:-1], last])


def _object_name(row: _Row, header: list[str], notes: _Notes) -> str | None:
    """The object a class table's row names, or None (with a warning) when it is skipped."""
    if not row.cells:
        return None
    if _too_wide(row, header, notes):
        return None
    cell = row.cells[0]
    image = _IMAGE.search(cell)
    if image is not None:
        before = clean_name(cell[:cell.find("![")] if "![" in cell else "")
        if not before:
            notes.skip(row, f"its first cell '{cell}' is an image, not an object name "
                            "(a cell shifted?)")
            return None
        notes.read_as(row, f"runs the object name and its image together (a '|' missing); "
                           f"read as the object '{before}'")
        return before
    if not cell:
        notes.skip(row, "its first cell, the object name, is empty (a cell shifted?)")
        return None
    if _placeholder(cell):
        notes.skip(row, "a placeholder, not an object name")
        return None
    return clean_name(cell)
