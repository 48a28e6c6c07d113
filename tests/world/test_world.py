"""World files: the shipped worlds, validation errors with file, line and field, round trip."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from homebot.errors import WorldError
from homebot.world import World, shipped_world_names

MINIMAL = """\
name: tiny
rooms:
  - {name: hall, polygon: [[0, 0], [4, 0], [4, 4], [0, 4]]}
  - {name: study, polygon: [[4, 0], [8, 0], [8, 4], [4, 4]]}
doors:
  - {name: study door, rooms: [hall, study], position: [4, 2]}
categories:
  - {name: drink, plural: drinks}
placements:
  - {name: table, category: table, room: study, center: [6, 2], size: [1, 1], holds: [drink]}
objects:
  - {name: cola, category: drink, placement: table}
people:
  - {name: Ann, room: hall, position: [1, 1]}
operator: Ann
robot:
  pose: [2, 2, 0]
"""


def test_apartment_has_what_the_issue_asks_for(apartment: World) -> None:
    rooms = set(apartment.rooms)
    assert {"kitchen", "living room", "bedroom", "bathroom", "office", "entrance"} <= rooms
    assert len(apartment.placements) >= 15
    assert len(apartment.objects) >= 30
    assert len({o.category for o in apartment.objects.values()}) >= 6
    assert len(apartment.people) >= 3
    assert apartment.operator is not None


def test_supermarket_has_three_shelves_a_start_and_a_customer(supermarket: World) -> None:
    holds = {tuple(p.holds) for p in supermarket.placements.values()}
    assert {("drink",), ("food",), ("bread",)} <= holds
    assert "start" in supermarket.placements
    assert supermarket.operator is not None and supermarket.operator.name == "customer"


def test_shipped_worlds_are_listed() -> None:
    assert {"apartment", "supermarket"} <= set(shipped_world_names())


def test_every_placement_gets_an_approach_pose_inside_its_room(apartment: World) -> None:
    for placement in apartment.placements.values():
        x, y = placement.approach.xy()
        assert apartment.room_at(x, y) == placement.room, placement.name


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "world.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def test_minimal_world_loads(tmp_path: Path) -> None:
    world = World.load(_write(tmp_path, MINIMAL))
    assert world.placement("table").room == "study"


def test_typo_in_a_field_names_file_line_and_suggests(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("category: table", "categroy: table"))
    with pytest.raises(WorldError) as error:
        World.load(path)
    message = str(error.value)
    assert str(path) in message
    assert "line 10" in message
    assert "placements.0.categroy" in message
    assert "did you mean 'category'" in message


def test_door_to_a_room_that_does_not_exist(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("rooms: [hall, study]", "rooms: [hall, studio]"))
    with pytest.raises(WorldError, match=r"line 6: doors\.0\.rooms: unknown room 'studio'; "
                                         r"did you mean 'study'"):
        World.load(path)


def test_object_on_an_unknown_placement(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("placement: table", "placement: tabel"))
    with pytest.raises(WorldError, match=r"objects\.0\.placement: unknown placement 'tabel'"):
        World.load(path)


def test_door_not_on_a_shared_wall(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("position: [4, 2]", "position: [2, 2]"))
    with pytest.raises(WorldError, match="not on the wall"):
        World.load(path)


def test_yaml_syntax_error_names_line_and_column(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("robot:\n  pose", "robot:\n pose: [\n  x"))
    with pytest.raises(WorldError, match=r"line \d+, column \d+: YAML syntax error"):
        World.load(path)


def test_missing_required_field(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("robot:\n  pose: [2, 2, 0]\n", ""))
    with pytest.raises(WorldError, match="robot: required field is missing"):
        World.load(path)


def test_unknown_world_name_lists_the_shipped_ones() -> None:
    with pytest.raises(WorldError, match="apartment"):
        World.load("palace")


@pytest.mark.parametrize("name", ["apartment", "supermarket"])
def test_round_trip_through_yaml(name: str, tmp_path: Path) -> None:
    world = World.load(name)
    path = tmp_path / f"{name}.yaml"
    world.save(path)
    again = World.load(path)
    assert again.model == world.model
    assert yaml.safe_load(path.read_text()) == world.to_dict()


def test_a_persons_height_is_drawn_as_declared_and_must_be_a_persons(tmp_path: Path) -> None:
    from homebot.sim.body_tracker import person_height

    ann = "{name: Ann, room: hall, position: [1, 1]}"
    tall = World.load(_write(tmp_path, MINIMAL.replace(ann, ann[:-1] + ", height: 1.93}")))
    assert person_height("Ann", tall.model.people[0]) == 1.93
    drawn = person_height("Ann", World.load(_write(tmp_path, MINIMAL)).model.people[0])
    assert 1.55 <= drawn <= 1.95
    path = _write(tmp_path, MINIMAL.replace(ann, ann[:-1] + ", height: -1.7}"))
    with pytest.raises(WorldError,
                       match=r"line 14: people\.0\.height: must be greater than or equal to 0\.5"):
        World.load(path)


def test_rooms_touching_along_a_rounded_diagonal_are_not_overlapping(tmp_path: Path) -> None:
    # A wall from (0, 0) to (3, 1.7), its corners rounded to the millimetre on one side
    # (as importers write them): the rooms cross by a hair, which is no overlap.
    text = MINIMAL.replace(
        "  - {name: hall, polygon: [[0, 0], [4, 0], [4, 4], [0, 4]]}\n"
        "  - {name: study, polygon: [[4, 0], [8, 0], [8, 4], [4, 4]]}\n",
        "  - {name: hall, polygon: [[0, 0], [3, 1.7], [3, 4], [0, 4]]}\n"
        "  - {name: study, polygon: [[0, 0], [8, 0], [8, 4], [3, 4], [3.0004, 1.7003]]}\n")
    text = text.replace("position: [4, 2]", "position: [1.5, 0.85]").replace(
        "center: [6, 2]", "center: [6, 1]")
    world = World.load(_write(tmp_path, text))
    assert set(world.rooms) == {"hall", "study"}


def test_rooms_overlapping_by_a_few_centimetres_are_refused_in_cm2(tmp_path: Path) -> None:
    path = _write(tmp_path, MINIMAL.replace("[[4, 0], [8, 0], [8, 4], [4, 4]]",
                                            "[[3.998, 0], [8, 0], [8, 4], [3.998, 4]]"))
    with pytest.raises(WorldError, match=r"room 'hall' overlaps room 'study' by 80 cm²"):
        World.load(path)
