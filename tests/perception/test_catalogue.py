"""The object catalogue in the world file: defaults per category, overrides, bad entries."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.cli import main
from homebot.errors import WorldError
from homebot.world import (
    CATEGORY_DEFAULTS,
    Shape,
    World,
    catalogue_entry,
    object_catalogue,
    shipped_world_names,
    surface_height,
)

WORLD = """\
name: tiny
rooms:
  - {name: hall, polygon: [[0, 0], [4, 0], [4, 4], [0, 4]]}
categories:
  - {name: drink, plural: drinks}
  - {name: gizmo, plural: gizmos, shape: sphere, dimensions: [0.1], colour: cyan, mass: 0.9}
placements:
  - {name: table, category: table, room: hall, center: [3, 2], size: [1, 1]}
  - {name: bench, category: seating, room: hall, center: [3, 3.4], size: [1, 0.4], height: 0.5}
objects:
  - {name: cola, category: drink, placement: table}
  - {name: can, category: drink, placement: table, shape: box, dimensions: [0.1, 0.2, 0.3],
     colour: [10, 20, 30], weight: 2.5}
  - {name: widget, category: gizmo, placement: table}
  - {name: tall widget, category: gizmo, placement: table, size: 0.3}
robot:
  pose: [1, 1, 0]
"""


def test_every_category_of_the_shipped_worlds_has_a_default() -> None:
    for name in shipped_world_names():
        world = World.load(name)
        for category in {obj.category for obj in world.objects.values()}:
            assert category.replace("_", " ") in CATEGORY_DEFAULTS, (name, category)


def test_defaults_overrides_and_category_fields() -> None:
    world = World.from_yaml_text(WORLD)
    cola = catalogue_entry(world, "cola")
    assert cola.shape is Shape.CYLINDER and cola.mass > 0 and 0.05 < cola.size < 0.3
    can = catalogue_entry(world, "can")
    assert (can.shape, can.dimensions, can.rgb, can.mass) == (
        Shape.BOX, (0.1, 0.2, 0.3), (10, 20, 30), 2.5)
    assert can.extent == (0.1, 0.2, 0.3) and can.size == 0.3
    widget = catalogue_entry(world, "widget")
    assert (widget.shape, widget.dimensions, widget.colour, widget.mass) == (
        Shape.SPHERE, (0.1,), "cyan", 0.9)
    assert catalogue_entry(world, "tall widget").size == pytest.approx(0.3)
    assert surface_height(world.placements["table"].model) == 0.75
    assert surface_height(world.placements["bench"].model) == 0.5


def test_defaulted_objects_of_one_category_differ() -> None:
    catalogue = object_catalogue(World.load("apartment"))
    drinks = [entry for entry in catalogue.values() if entry.category == "drink"]
    assert len({(entry.colour, entry.dimensions) for entry in drinks}) == len(drinks)
    assert object_catalogue(World.load("apartment")) == catalogue  # stable by name


@pytest.mark.parametrize(("old", "new", "expected"), [
    ("dimensions: [0.1, 0.2, 0.3]", "dimensions: [0.1, -0.2, 0.3]", "greater than 0"),
    ("shape: box", "shape: pyramid", "box"),
    ("colour: cyan", "colour: sky", "'sky' is no colour"),
    ("colour: [10, 20, 30]", "colour: [10, 20, 300]", "is no colour"),
    ("dimensions: [0.1, 0.2, 0.3]", "dimensions: [0.1, 0.2]", "a box takes 3 dimension"),
])
def test_bad_catalogue_entries_name_file_and_line(tmp_path: Path, old: str, new: str,
                                                   expected: str,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert old in WORLD
    text = WORLD.replace(old, new, 1)
    line = next(number for number, row in enumerate(text.splitlines(), 1) if new in row)
    path = tmp_path / "bad.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(WorldError) as error:
        World.load(path)
    assert expected in str(error.value)
    assert str(path) in str(error.value)
    assert f"line {line}" in str(error.value) or f"line {line - 1}" in str(error.value)
    assert main(["world", "check", str(path)]) == 2
    err = capsys.readouterr().err
    assert expected in err and "Traceback" not in err


def test_the_catalogue_survives_a_round_trip() -> None:
    world = World.from_yaml_text(WORLD)
    again = World.from_dict(world.to_dict())
    assert object_catalogue(again) == object_catalogue(world)
    assert again.placements["bench"].model.height == 0.5
