"""A playable world from a RoboCup@Home data directory."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from homebot.app import RunSettings, build_run
from homebot.cli import main
from homebot.errors import WorldError
from homebot.language import Vocabulary, parse_command
from homebot.sim import PERSON_PREFIX
from homebot.world import CATEGORY_DEFAULTS, World, defaults_for
from homebot.world.masses import known_mass
from homebot.world.robocup import import_robocup, read_robocup_data, world_from_robocup

SHARED = Path(__file__).resolve().parents[3] / "shared" / "data" / "robocup" / "CompetitionTemplate"

NAMES = "## Names\n| Names |\n| --- |\n| Ada |\n| Bo |\n| Cy |\n"
ROOMS = "## Rooms\n| Name |\n| --- |\n| kitchen |\n| bedroom |\n| study room |\n"
LOCATIONS = """## Locations
| Number | Name | Object Category
| --- | --- | --- |
| 1 | bed (p) |
| 2 | kitchen table (p) | dishes |
| 3 | fridge (p) | drinks |
| 4 | lamp |
| 5 | entrance |
"""
OBJECTS = """# Class drinks (drink)
| Objectname | Image |
|:---:|:---:|
| orange_juice | ![](a.jpg) |
| cola | ![](b.jpg) |

# Class dishes (dish)
| Objectname | Image |
:---:|:---:
| cup | ![](c.png) |

# Class toys (toy)
| Objectname | Image |
:---:|:---:
| dice | ![](d.png) |
"""


def write_directory(root: Path, **overrides: str) -> Path:
    files = {"names/names.md": NAMES, "maps/room_names.md": ROOMS,
             "maps/location_names.md": LOCATIONS, "objects/objects.md": OBJECTS}
    files.update({key.replace("__", "/") + ".md": value for key, value in overrides.items()})
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text, encoding="utf-8")
    return root


def test_reads_the_tables(tmp_path: Path) -> None:
    data = read_robocup_data(write_directory(tmp_path))
    assert data["names"] == ["Ada", "Bo", "Cy"]
    assert data["rooms"] == ["kitchen", "bedroom", "study room"]
    assert data["locations"][1] == {"name": "kitchen table", "placeable": True,
                                    "category": "dishes"}
    assert [entry["name"] for entry in data["classes"]] == ["drink", "dish", "toy"]


def test_builds_a_valid_world(tmp_path: Path) -> None:
    world = World.from_dict(world_from_robocup(write_directory(tmp_path)))
    assert set(world.rooms) == {"kitchen", "bedroom", "study room"}
    assert set(world.placements) == {"bed", "kitchen table", "fridge", "lamp", "entrance"}
    assert world.placements["fridge"].holds == ["drink"]
    assert world.objects["orange juice"].placement == "fridge"
    assert world.objects["cup"].placement == "kitchen table"
    assert world.categories["drink"].plural == "drinks"
    assert set(world.people) == {"Ada", "Bo", "Cy"}
    assert world.room_at(*world.robot.pose.xy()) is not None


def test_objects_without_a_home_go_on_a_placeable_location(tmp_path: Path) -> None:
    world = World.from_dict(world_from_robocup(write_directory(tmp_path)))
    assert world.objects["dice"].placement in {"bed", "kitchen table", "fridge", "lamp"}


def test_every_room_is_reachable_through_doors(tmp_path: Path) -> None:
    world = World.from_dict(world_from_robocup(write_directory(tmp_path)))
    reached, frontier = {"kitchen"}, ["kitchen"]
    while frontier:
        room = frontier.pop()
        for door in world.doors.values():
            if room in door.rooms:
                other = door.rooms[1] if door.rooms[0] == room else door.rooms[0]
                if other not in reached:
                    reached.add(other)
                    frontier.append(other)
    assert reached == set(world.rooms)


def test_same_directory_same_world(tmp_path: Path) -> None:
    directory = write_directory(tmp_path)
    assert world_from_robocup(directory) == world_from_robocup(directory)


def test_missing_file_is_a_world_error(tmp_path: Path) -> None:
    directory = write_directory(tmp_path)
    (directory / "maps" / "room_names.md").unlink()
    with pytest.raises(WorldError, match=r"room_names\.md"):
        world_from_robocup(directory)


def test_not_a_directory_is_a_world_error(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="not a directory"):
        world_from_robocup(tmp_path / "nowhere")


def test_empty_table_is_a_world_error(tmp_path: Path) -> None:
    directory = write_directory(tmp_path, names__names="## Names\n| Names |\n| --- |\n")
    with pytest.raises(WorldError, match="no names"):
        world_from_robocup(directory)


def test_a_room_named_like_a_location_is_a_world_error(tmp_path: Path) -> None:
    rooms = ROOMS + "| bed |\n"
    with pytest.raises(WorldError, match="both a room and a location"):
        world_from_robocup(write_directory(tmp_path, maps__room_names=rooms))


@pytest.mark.acceptance
def test_the_competition_template_builds_a_world() -> None:
    if not SHARED.is_dir():
        pytest.skip("the shared acceptance data (../shared/data) is absent")
    world = World.from_dict(world_from_robocup(SHARED))
    assert len(world.rooms) == 5 and len(world.placements) == 25
    assert len(world.objects) == 39 and len(world.people) == 10


# ---------------------------------------------------------------- real competition data (issue 14)

PLACEHOLDERS = Path(__file__).resolve().parent / "data" / "robocup_placeholders"


def test_placeholder_rows_are_skipped_with_a_warning() -> None:
    imported = import_robocup(PLACEHOLDERS)
    skipped = [warning for warning in imported.warnings if "location_names.md" in warning]
    assert len(skipped) == 3
    assert all("placeholder" in warning for warning in skipped)
    assert any("'| 4 | - |'" in warning for warning in skipped)
    names = {placement["name"] for placement in imported.data["placements"]}
    assert "-" not in names and "" not in names and len(names) == 15


def test_the_operator_stands_at_the_start_beside_the_robot() -> None:
    data = import_robocup(PLACEHOLDERS).data
    world = World.from_dict(data)
    assert world.operator is not None and world.operator.name == "Adel"
    robot = world.robot.pose
    assert math.dist(world.operator.position, robot.xy()) < 1.5
    assert world.placements["entrance"].approach.xy() == pytest.approx(robot.xy(), abs=0.5)


def test_placements_go_to_their_common_sense_rooms() -> None:
    world = World.from_dict(import_robocup(PLACEHOLDERS).data)
    expected = {"kitchen table": "kitchen", "refrigerator": "kitchen", "bed": "bedroom",
                "bedside table": "bedroom", "desk": "office", "sofa": "living room",
                "side tables": "living room"}
    assert {name: world.placements[name].room for name in expected} == expected


def test_a_rooms_file_overrides_the_table(tmp_path: Path) -> None:
    rooms = tmp_path / "rooms.yaml"
    rooms.write_text("kitchen table: office\nsink: [garage, bathroom]\n", encoding="utf-8")
    world = World.from_dict(import_robocup(PLACEHOLDERS, rooms_file=rooms).data)
    assert world.placements["kitchen table"].room == "office"
    assert world.placements["sink"].room == "bathroom"


@pytest.mark.parametrize("text", ["- kitchen\n", "sink: 3\n", "sink: [\n"])
def test_a_bad_rooms_file_is_a_world_error(tmp_path: Path, text: str) -> None:
    rooms = tmp_path / "rooms.yaml"
    rooms.write_text(text, encoding="utf-8")
    with pytest.raises(WorldError, match=r"rooms\.yaml"):
        import_robocup(PLACEHOLDERS, rooms_file=rooms)


def test_bring_me_a_coke_from_the_kitchen_table_succeeds_in_the_imported_world(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    output = tmp_path / "world.yaml"
    assert main(["world", "from-robocup", str(PLACEHOLDERS), "-o", str(output)]) == 0
    captured = capsys.readouterr()
    assert captured.err.count("warning:") == 4  # three placeholder rows, no mass for noodles
    text = output.read_text(encoding="utf-8")
    assert "position: [" in text and "polygon: [[" in text  # flow-style coordinates
    assert "operator: Adel" in text
    status = main(["do", "bring me a coke from the kitchen table", "--world", str(output),
                   "--json"])
    report = json.loads(capsys.readouterr().out)
    assert status == 0 and report["success"]
    assert [step["skill"] for step in report["steps"]] == [
        "navigate", "find_object", "pick", "navigate", "give"]
    assert report["steps"][0]["args"] == {"to": "kitchen table"}
    # Judged by ground truth, not by the report: the simulator has the coke with Adel.
    world = World.load(output)
    run = build_run(RunSettings(world=world))
    run.run(parse_command("bring me a coke from the kitchen table",
                          Vocabulary.from_world(world)).to_task())
    assert run.simulation.object_location["coke"] == PERSON_PREFIX + "Adel"


def test_an_unknown_category_is_a_warning_naming_the_input_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    directory = write_directory(tmp_path / "data", maps__location_names=LOCATIONS.replace(
        "| fridge (p) | drinks |", "| fridge (p) | sodas |"))
    assert main(["world", "from-robocup", str(directory), "-o", str(tmp_path / "w.yaml")]) == 0
    err = capsys.readouterr().err
    assert (f"warning: {directory / 'maps' / 'location_names.md'}: line 6: location 'fridge' "
            "names the object category 'sodas', which objects/objects.md does not list "
            "(known: dishes, drinks, toys)") in err
    assert World.load(tmp_path / "w.yaml").placements["fridge"].holds == []


@pytest.mark.parametrize(("override", "expected"), [
    ({"names__names": NAMES.replace("| Bo |", "| Kitchen |")},
     "names/names.md: line 5: people.1.name: 'Kitchen' is also a room name ('kitchen', but for "
     "accents or case) (rooms.0, {root}/maps/room_names.md: line 4)"),
    ({"maps__location_names": LOCATIONS.replace("| lamp |", "| 4lamp |")},
     "maps/location_names.md: line 7: placements.3.name: String should match pattern"),
    ({"objects__objects": OBJECTS.replace("| dice |", "| Ada |")},
     "objects/objects.md: line 15: objects.3.name: 'Ada' is also a person name (people.0, "
     "{root}/names/names.md: line 4)"),
])
def test_errors_in_an_imported_world_name_the_input_file_and_line(
        tmp_path: Path, override: dict[str, str], expected: str,
        capsys: pytest.CaptureFixture[str]) -> None:
    directory = write_directory(tmp_path, **override)
    assert main(["world", "from-robocup", str(directory), "-o", str(tmp_path / "w.yaml")]) == 2
    err = capsys.readouterr().err
    assert expected.format(root=directory) in err.replace("\n", "")
    assert not (tmp_path / "w.yaml").exists()


# ---------------------------------------------------------------- masses (issue 43)


def test_objects_weigh_what_the_mass_catalogue_says(tmp_path: Path) -> None:
    imported = import_robocup(write_directory(tmp_path))
    weights = {entry["name"]: entry["weight"] for entry in imported.data["objects"]}
    for name in ("orange juice", "cola", "cup", "dice"):
        known = known_mass(name)
        assert known is not None and weights[name] == known.mass
    assert weights["dice"] == 0.0052 and weights["cup"] == 0.118  # YCB 062 dice, 025 mug
    assert not [warning for warning in imported.warnings if "objects.md" in warning]


def test_an_object_without_a_known_mass_takes_its_category_default_with_a_warning(
        tmp_path: Path) -> None:
    objects = OBJECTS.replace("| dice |", "| kazoo |").replace("| cola |", "| elixir |") + (
        "\n# Class gizmos (gizmo)\n| Objectname | Image |\n|---|---|\n| widget | x |\n")
    imported = import_robocup(write_directory(tmp_path, objects__objects=objects))
    weights = {entry["name"]: entry["weight"] for entry in imported.data["objects"]}
    assert weights["kazoo"] == defaults_for("toy").mass == CATEGORY_DEFAULTS["toy"].mass
    assert weights["elixir"] == CATEGORY_DEFAULTS["drink"].mass
    path = tmp_path / "objects" / "objects.md"
    assert [warning for warning in imported.warnings if "objects.md" in warning] == [
        f"{path}: line 5: no typical mass known for the object 'elixir' "
        "(src/homebot/data/robocup/masses.yaml); took the category default, 0.5 kg (drink)",
        f"{path}: line 15: no typical mass known for the object 'kazoo' "
        "(src/homebot/data/robocup/masses.yaml); took the category default, 0.2 kg (toy)",
        f"{path}: line 20: no typical mass known for the object 'widget' "
        "(src/homebot/data/robocup/masses.yaml); took the category default, 0.3 kg (an "
        "undescribed category)"]


FRUITS = OBJECTS + """
# Class fruits (fruit)
| Objectname | Image |
|:---:|:---:|
| apple | ![](a.png) |
| strawberry | ![](s.png) |
| banana | ![](b.png) |
| plum | ![](p.png) |
"""


def test_the_lightest_fruit_is_the_lightest_by_the_catalogue(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    directory = write_directory(tmp_path / "data", objects__objects=FRUITS,
                               maps__location_names=LOCATIONS + "| 6 | desk (p) | fruits |\n")
    output = tmp_path / "world.yaml"
    assert main(["world", "from-robocup", str(directory), "-o", str(output)]) == 0
    world = World.load(output)
    fruits = [o for o in world.model.objects if o.category == "fruit"]
    masses = {o.name: known_mass(o.name).mass for o in fruits}  # type: ignore[union-attr]
    assert {o.name: o.weight for o in fruits} == masses
    lightest = min(masses, key=masses.__getitem__)
    assert lightest == "strawberry"  # YCB 012, 18 g; the plum is 25 g
    capsys.readouterr()
    assert main(["do", "Which is the lightest fruit on the desk? Tell me.", "--world",
                 str(output), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert "The lightest fruit on the desk is the strawberry." in json.dumps(report)
