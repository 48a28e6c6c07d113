"""Physical sanity: sizes within the home, nothing outside its room, no overlaps, and no name
that two kinds of entity share; every error names the file, the line and by how much."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.cli import main
from homebot.errors import WorldError
from homebot.world import World, shipped_world_names, shipped_world_path
from homebot.world.physical import length_text, overlapping_pairs, reach_beyond

ROOT = Path(__file__).resolve().parents[2]
SHARED_ROBOCUP = ROOT.parent / "shared" / "data" / "robocup"

# A 5 m kitchen beside a 4 m hall; the tests below count its lines (people: line 16).
HOME = """\
name: small
rooms:
  - {{name: kitchen, polygon: [[0, 0], [5, 0], [5, 4], [0, 4]]}}
  - {{name: hall, polygon: [[5, 0], [9, 0], [9, 4], [5, 4]]}}
doors:
  - {{name: hall door, rooms: [kitchen, hall], position: [5, 2]}}
placements:
  - {{name: counter, category: table, room: kitchen, center: [1, 3.6], size: [2, 0.6]}}
  - {{name: fridge, category: storage, room: kitchen, center: {fridge_center}, size: {fridge_size}}}
  - {{name: sofa, category: seating, room: hall, center: [7, 3.4], size: [2, 0.8]}}
categories:
  - {{name: drink, plural: drinks}}
objects:
  - {{name: cola, category: drink, placement: fridge}}
people:
  - {{name: {person}, room: hall, position: {person_position}, posture: {posture}}}
robot:
  pose: {robot_pose}
"""
SANE = {"fridge_center": "[4.6, 3.6]", "fridge_size": "[0.7, 0.7]", "person": "Alex",
        "person_position": "[7, 1.5]", "posture": "standing", "robot_pose": "[2.5, 1.5, 0]"}


def _home(tmp_path: Path, **changes: str) -> Path:
    path = tmp_path / "small.yaml"
    path.write_text(HOME.format(**{**SANE, **changes}), encoding="utf-8")
    return path


def _refused(path: Path) -> str:
    with pytest.raises(WorldError) as error:
        World.load(path)
    return str(error.value)


def test_the_sane_home_loads_and_a_fetch_is_possible(tmp_path: Path) -> None:
    world = World.load(_home(tmp_path))
    assert world.placement("fridge").footprint.area == pytest.approx(0.49)


@pytest.mark.parametrize(("changes", "expected"), [
    ({"fridge_size": "[1.0e+308, 0.7]"},
     "small.yaml: line 9: placements.1.size: width and depth are metres, at most 100 "
     "(furniture, not a house) (got [1e+308, 0.7]); size is its width (along x) and depth"),
    ({"fridge_size": "[99, 0.7]"},
     "small.yaml: line 9: placements.1.size: the fridge (99 × 0.7 m around [4.6, 3.6]) "
     "reaches 49.1 m beyond the walls of room 'kitchen'"),
    ({"fridge_center": "[2.5, 2]", "fridge_size": "[100, 0.7]"},
     "reaches 47.5 m beyond the walls of room 'kitchen'; give its true size"),
    # half inside the wall: the fridge's back 35 cm past the kitchen's outline
    ({"fridge_center": "[2.5, 4]"}, "reaches 35 cm beyond the walls of room 'kitchen'"),
    ({"person_position": "[12, 1.5]"},
     "line 16: people.0.position: [12.0, 1.5] lies 3 m outside room 'hall'; move them"),
    ({"person_position": "[1.0e+308, 1.5]"},
     "line 16: people.0.position.0: must be less than or equal to 100000 (got 1e+308)"),
    ({"robot_pose": "[2.5, -2, 0]"},
     "line 18: robot.pose: the robot at (2.5, -2) is outside every room (2 m from the "
     "nearest, 'kitchen')"),
])
def test_what_does_not_fit_in_its_room_is_refused_by_how_much(
        tmp_path: Path, changes: dict[str, str], expected: str) -> None:
    assert expected in _refused(_home(tmp_path, **changes))


def test_world_check_refuses_a_huge_placement_in_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["world", "check", str(_home(tmp_path, fridge_size="[1.0e+308, 0.7]"))])
    err = capsys.readouterr().err
    assert status == 2 and "placements.1.size" in err and "at most 100" in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


@pytest.mark.parametrize(("changes", "expected"), [
    ({"fridge_center": "[1.6, 3.6]"},
     "line 9: placements.1.center: the fridge overlaps the counter (placements.0, line 8) "
     "by 60 cm; move one of them"),
    ({"person_position": "[7, 3.3]"},
     "line 16: people.0.position: Alex stands 30 cm inside the sofa; move them beside it"),
])
def test_physical_overlaps_are_refused_in_centimetres(
        tmp_path: Path, changes: dict[str, str], expected: str) -> None:
    assert expected in _refused(_home(tmp_path, **changes))


@pytest.mark.parametrize("posture", ["sitting", "lying"])
def test_a_person_may_sit_or_lie_on_furniture(tmp_path: Path, posture: str) -> None:
    world = World.load(_home(tmp_path, person_position="[7, 3.3]", posture=posture))
    assert world.person("Alex").posture.value == posture


@pytest.mark.parametrize(("person", "expected"), [
    ("hall", "line 16: people.0.name: 'hall' is also a room name (rooms.1, line 4), so a "
             "command naming it could mean either; rename the person"),
    ("Hall", "'Hall' is also a room name ('hall', but for accents or case)"),
    ("Sofa", "'Sofa' is also a placement name ('sofa', but for accents or case) "
             "(placements.2, line 10)"),
    ("cola", "'cola' is also a person name (people.0, line 16)"),
    ("hall door", "'hall door' is also a door name (doors.0, line 6)"),
])
def test_a_name_two_kinds_share_is_refused(tmp_path: Path, person: str, expected: str) -> None:
    assert expected in _refused(_home(tmp_path, person=person))


def test_an_object_may_be_named_after_its_category(tmp_path: Path) -> None:
    text = HOME.format(**SANE).replace("name: cola, category: drink", "name: drink, "
                                       "category: drink")
    assert "drink" in World.from_yaml_text(text).objects


def _shipped_and_benchmark_worlds() -> list[Path]:
    flats = sorted((ROOT / "benchmarks" / "flats").glob("*.yaml"))
    return [shipped_world_path(name) for name in shipped_world_names()] + flats + [
        ROOT / "tests" / "world" / "data" / "casa.yaml"]


@pytest.mark.parametrize("path", _shipped_and_benchmark_worlds(), ids=lambda path: path.stem)
def test_shipped_and_benchmark_worlds_are_physically_sane(path: Path) -> None:
    assert World.load(path).placements


def test_imported_worlds_are_physically_sane() -> None:
    from homebot.world.pyrobosim import import_pyrobosim
    from homebot.world.robocup import import_robocup

    for name in ("pyrobosim_flat.yaml", "pyrobosim_studio.yaml"):
        imported = import_pyrobosim(ROOT / "tests/world/data" / name)
        assert World.from_dict(imported.data).placements
    placeholders = import_robocup(ROOT / "tests/world/data/robocup_placeholders")
    assert World.from_dict(placeholders.data).placements


@pytest.mark.acceptance
def test_the_shared_robocup_worlds_import_sane() -> None:
    from homebot.world.robocup import import_robocup

    if not SHARED_ROBOCUP.is_dir():
        pytest.skip("the shared acceptance data (../shared/data) is absent")
    for directory in sorted(SHARED_ROBOCUP.iterdir()):
        assert World.from_dict(import_robocup(directory).data).people


def test_the_geometry_measures_what_it_says() -> None:
    from shapely.geometry import box

    room = box(0, 0, 5, 4)
    assert reach_beyond(box(4, 1, 6, 2), room) == pytest.approx(1.0)
    assert reach_beyond(box(1, 1, 2, 2), room) == 0.0
    pairs = overlapping_pairs([box(0, 0, 2, 1), box(5, 5, 6, 6), box(1.5, 0, 3, 1)])
    assert [(first, second, round(depth, 3)) for first, second, depth in pairs] == [(0, 2, 0.5)]
    assert overlapping_pairs([box(0, 0, 1, 1), box(1, 0, 2, 1)]) == []  # touching is fine
    assert (length_text(0.35), length_text(47.5), length_text(5e307)) == \
        ("35 cm", "47.5 m", "5e+307 m")


def test_people_inside_furniture_are_found_among_many() -> None:
    from shapely.geometry import box

    from homebot.world.physical import points_inside

    tables = [box(x, 0, x + 1, 1) for x in range(0, 2000, 2)]
    people = [(x + 0.5, 0.5) if x % 500 == 0 else (x + 1.5, 0.5) for x in range(0, 2000, 2)]
    assert points_inside(tables, people) == [(0, 0, 0.5), (250, 250, 0.5), (500, 500, 0.5),
                                             (750, 750, 0.5)]


def test_an_object_on_a_placement_not_meant_for_it_is_a_warning_with_its_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # a towel in the fridge: allowed (a home has things to tidy away), but said
    text = HOME.format(**SANE).replace(
        "size: [0.7, 0.7]}", "size: [0.7, 0.7], holds: [drink]}").replace(
        "  - {name: drink, plural: drinks}\n",
        "  - {name: drink, plural: drinks}\n  - {name: towel, plural: towels}\n").replace(
        "  - {name: cola, category: drink, placement: fridge}\n",
        "  - {name: cola, category: drink, placement: fridge}\n"
        "  - {name: bath towel, category: towel, placement: fridge}\n")
    path = tmp_path / "towel.yaml"
    path.write_text(text, encoding="utf-8")
    assert World.load(path).warnings == [
        f"{path}: line 16: objects.1.placement: the bath towel (towel) is on the fridge, which "
        "holds drink: a tidy-up would move it; if it belongs there, add towel to the "
        "fridge's holds"]  # not the cola
    assert main(["world", "check", str(path)]) == 0
    err = capsys.readouterr().err
    assert err.startswith(f"warning: {path}: line 16:") and len(err.splitlines()) == 1
