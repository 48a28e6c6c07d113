"""``world check`` warns of a door leaf that swings over a placement's approach spot, with
the file, the line and what to move."""

from __future__ import annotations

from pathlib import Path

import pytest
from shapely.geometry import Point

from homebot.cli import main
from homebot.world import World
from homebot.world.swings import door_swing

_FLAT = """name: landing_with_a_console
rooms:
  - {{name: landing, polygon: [[3, 2.5], [5.5, 2.5], [5.5, 4.5], [3, 4.5]]}}
  - {{name: kitchen, polygon: [[0, 0], [3, 0], [3, 4.5], [0, 4.5]]}}
doors:
  - {{name: kitchen door, rooms: [kitchen, landing], position: [3, 3.5], width: 0.8,
     opening: {opening}, hinge: north, swings_into: landing}}
placements:
  - {{name: console, category: table, room: landing, center: [3.55, 4.3], size: [0.8, 0.3]}}
  - {{name: fridge, category: appliance, room: kitchen, center: [0.4, 4.0], size: [0.7, 0.7]}}
robot:
  pose: [4.2, 3.0, 0.0]
"""


def test_the_swing_runs_from_shut_to_the_opening() -> None:
    world = World.from_yaml_text(_FLAT.format(opening=60))
    swing = door_swing(world, "kitchen door")
    assert swing is not None
    # hinged at the north jamb (3, 3.9): the leaf shut reaches the south jamb, and at 60
    # degrees into the landing its tip stands at (3.69, 3.5); the kitchen side stays clear
    assert swing.distance(Point(3.0, 3.15)) < 0.03
    assert swing.distance(Point(3.69, 3.5)) < 0.03
    assert swing.distance(Point(2.6, 3.5)) > 0.3
    assert door_swing(World.from_yaml_text(_FLAT.replace(
        "\n     opening: {opening}, hinge: north, swings_into: landing", "").format()),
        "kitchen door") is None


def test_a_leaf_over_an_approach_spot_is_warned_of_with_its_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "flat.yaml"
    path.write_text(_FLAT.format(opening=60))
    assert main(["world", "check", str(path)]) == 0  # a warning, not an error
    err = capsys.readouterr().err
    assert f"{path}: line 9: placements.0.center" in err
    assert "kitchen door's leaf" in err and "move the console" in err
    assert "fridge" not in err


def test_a_leaf_barely_ajar_clear_of_the_spot_is_not_warned_of() -> None:
    assert World.from_yaml_text(_FLAT.format(opening=15)).warnings == []
