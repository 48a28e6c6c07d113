"""Reading a RoboCup@Home data directory: malformed rows are warned about, never merged."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.world import World
from homebot.world.robocup import import_robocup
from homebot.world.robocup_tables import read_robocup_data

NAMES = "## Names\n| Names |\n| --- |\n| Ada |\n| Bo |\n"
ROOMS = "## Rooms\n| Name |\n| --- |\n| kitchen |\n| bedroom |\n"
HEADER = "## Locations\n| Number | Name | Object Category\n| --- | --- | --- |\n"
OBJECTS = """# Class drinks (drink)
| Objectname | Image |
|:---:|:---:|
| cola | ![](cola.jpg) |

# Class dishes (dish)
| Objectname | Image |
|:---:|:---:|
| cup | ![](cup.png) |
"""


def write(root: Path, locations: str = "| 1 | bed (p) |\n", objects: str = OBJECTS,
          names: str = NAMES, rooms: str = ROOMS) -> Path:
    for name, text in (("names/names.md", names), ("maps/room_names.md", rooms),
                       ("maps/location_names.md", HEADER + locations),
                       ("objects/objects.md", objects)):
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text, encoding="utf-8")
    return root


def read(root: Path, **files: str) -> tuple[dict[str, object], list[str]]:
    warnings: list[str] = []
    return read_robocup_data(write(root, **files), warnings), warnings


# Line 4 is the first data row of the locations table (after the title, header, separator).
@pytest.mark.parametrize(("row", "problem"), [
    ("| 2 | kitchen | table (p) | dishes |", "4 cells where the header"),
    ("| 2 | kitchen table (p) | dishes | drinks |", "4 cells where the header"),
    ("| kitchen table (p) | dishes |", "first cell 'kitchen table (p)' is not a number"),
    ("| 2 | kitchen table (p) dishes | drinks |", "goes on after '(p)'"),
])
def test_a_malformed_location_row_is_skipped_with_its_file_line_and_problem(
        tmp_path: Path, row: str, problem: str) -> None:
    data, warnings = read(tmp_path, locations=f"| 1 | bed (p) |\n{row}\n| 3 | sink (p) |\n")
    assert [location["name"] for location in data["locations"]] == ["bed", "sink"]
    assert len(warnings) == 1
    path = tmp_path / "maps" / "location_names.md"
    assert warnings[0].startswith(f"{path}: line 5: skipped the row '{row}': ")
    assert problem in warnings[0]
    assert data["lines"]["locations"] == [f"{path}: line 4", f"{path}: line 6"]


@pytest.mark.parametrize(("row", "expected", "how"), [
    ("| 2 kitchen table (p) | dishes |",
     {"name": "kitchen table", "placeable": True, "category": "dishes"},
     "read as number 2, name 'kitchen table (p)'"),
    ("| 2 | kitchen table (p) dishes |",
     {"name": "kitchen table", "placeable": True, "category": "dishes"},
     "read as location 'kitchen table', object category 'dishes'"),
    ("| 2 | kitchen table dishes |",
     {"name": "kitchen table", "placeable": False, "category": "dishes"},
     "ends with the object category 'dishes'"),
    ("| | kitchen table (p) | dishes |",
     {"name": "kitchen table", "placeable": True, "category": "dishes"}, "has no number"),
    ("| 2 | kitchen table | (p) dishes |",
     {"name": "kitchen table", "placeable": True, "category": "dishes"},
     "'(p)' in the category column"),
])
def test_a_row_with_one_possible_reading_is_read_so_with_a_warning(
        tmp_path: Path, row: str, expected: dict[str, object], how: str) -> None:
    data, warnings = read(tmp_path, locations=f"| 1 | bed (p) |\n{row}\n")
    assert data["locations"][1] == expected
    assert len(warnings) == 1 and "line 5" in warnings[0] and how in warnings[0]


def test_well_formed_rows_give_no_warning(tmp_path: Path) -> None:
    rows = ("| 1 | bed (p) |\n| 2 | kitchen table (p) | dishes |\n| 3 | lamp | |\n"
            "4 | sink (p) | drinks\n")
    data, warnings = read(tmp_path, locations=rows)
    assert warnings == []
    assert [(location["name"], location["placeable"], location["category"])
            for location in data["locations"]] == [
        ("bed", True, None), ("kitchen table", True, "dishes"), ("lamp", False, None),
        ("sink", True, "drinks")]


def test_a_names_row_with_two_cells_is_skipped_not_merged(tmp_path: Path) -> None:
    data, warnings = read(tmp_path, names=NAMES + "| Cy | Dee |\n|  | Eve |\n")
    assert data["names"] == ["Ada", "Bo"]
    path = tmp_path / "names" / "names.md"
    assert warnings == [
        f"{path}: line 6: skipped the row '| Cy | Dee |': it has 2 cells where the header "
        "'Names' has 1 (a '|' too many?)",
        f"{path}: line 7: skipped the row '|  | Eve |': its first cell is empty (a cell "
        "shifted?)"]


def test_object_rows_with_a_missing_or_extra_bar_are_warned_about(tmp_path: Path) -> None:
    objects = OBJECTS + ("| juice_pack ![](juice.png) |\n| milk | ![](m.png) | ![](n.png) |\n"
                         "| ![](spoon.png) |\n")
    data, warnings = read(tmp_path, objects=objects)
    dishes = data["classes"][1]
    assert dishes["objects"] == ["cup", "juice pack"]
    path = tmp_path / "objects" / "objects.md"
    assert len(warnings) == 3
    assert warnings[0].startswith(f"{path}: line 10: the row '| juice_pack ![](juice.png) |' "
                                  "runs the object name and its image together")
    assert warnings[1].startswith(f"{path}: line 11: skipped the row") and "3 cells" in \
        warnings[1]
    assert warnings[2].startswith(f"{path}: line 12: skipped the row") and "is an image" in \
        warnings[2]


def test_object_rows_under_no_class_heading_are_warned_about(tmp_path: Path) -> None:
    objects = "| Objectname | Image |\n|---|---|\n| stray | ![](s.png) |\n" + OBJECTS
    data, warnings = read(tmp_path, objects=objects)
    assert [entry["objects"] for entry in data["classes"]] == [["cola"], ["cup"]]
    assert len(warnings) == 2 and all("under no '# Class" in w for w in warnings)


@pytest.mark.parametrize("heading", [
    "# Class cleaning supplies (cleaning supply)",
    "# Class cleaning_supplies (cleaning_supply)",
    "## Class Cleaning Supplies  (Cleaning Supply) ",
    "# class cleaning_supplies(cleaning supply)",
])
def test_a_multi_word_category_is_kept(tmp_path: Path, heading: str) -> None:
    objects = OBJECTS + f"\n{heading}\n| Objectname | Image |\n|---|---|\n| sponge | x |\n"
    locations = "| 1 | shelf (p) | cleaning supplies |\n| 2 | sink (p) | cleaning_supplies |\n"
    data, warnings = read(tmp_path, objects=objects, locations=locations)
    assert warnings == []
    assert data["classes"][2] == {"plural": "cleaning supplies", "name": "cleaning supply",
                                  "objects": ["sponge"]}
    world = World.from_dict(import_robocup(tmp_path).data)
    assert world.categories["cleaning supply"].plural == "cleaning supplies"
    assert world.objects["sponge"].category == "cleaning supply"
    assert world.placements["shelf"].holds == ["cleaning supply"]
    assert world.placements["sink"].holds == ["cleaning supply"]


def test_a_class_heading_without_its_singular_takes_one_with_a_warning(tmp_path: Path) -> None:
    objects = OBJECTS + "\n# Class cleaning supplies\n| Objectname | Image |\n|---|---|\n" \
        "| sponge | x |\n"
    data, warnings = read(tmp_path, objects=objects)
    assert data["classes"][2]["name"] == "cleaning supply"
    assert len(warnings) == 1 and "gives no singular" in warnings[0]


def test_a_table_without_a_number_column_reads_names_from_the_first(tmp_path: Path) -> None:
    write(tmp_path)
    (tmp_path / "maps" / "location_names.md").write_text(
        "| Name | Object Category |\n|---|---|\n| bed (p) |\n| fridge (p) | drinks |\n",
        encoding="utf-8")
    warnings: list[str] = []
    data = read_robocup_data(tmp_path, warnings)
    assert [(entry["name"], entry["category"]) for entry in data["locations"]] == [
        ("bed", None), ("fridge", "drinks")]
    assert warnings == []
