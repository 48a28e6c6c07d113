"""The robot's footprint: where a disc of the robot's radius fits on the floor of a world."""

from __future__ import annotations

import pytest

from homebot.errors import WorldError
from homebot.world import World, shipped_world_names

TWO_ROOMS = """\
name: tiny
rooms:
  - {{name: hall, polygon: [[0, 0], [4, 0], [4, 4], [0, 4]]}}
  - {{name: study, polygon: [[4, 0], [8, 0], [8, 4], [4, 4]]}}
doors:
  - {{name: study door, rooms: [hall, study], position: [4, 2]}}
placements:
  - {{name: table, category: table, room: study, center: [6, 2], size: [1, 1]}}
robot:
  pose: [{x}, {y}, 0]
"""


def _world(x: float, y: float) -> World:
    return World.from_yaml_text(TWO_ROOMS.format(x=x, y=y), "tiny.yaml")


@pytest.mark.parametrize("name", shipped_world_names())
def test_shipped_worlds_start_the_robot_on_free_floor(name: str) -> None:
    world = World.load(name)
    assert world.footprint_problem(*world.robot.pose.xy()) is None


@pytest.mark.parametrize(("x", "y", "expected"), [
    (6.0, 2.0, "is inside the table"),
    (6.6, 2.0, "0.10 m from the table"),
    (4.0, 1.0, "is inside a wall"),
    (4.2, 1.0, "0.15 m from a wall"),
    (0.04, 3.0, "is inside a wall"),
    (0.1, 3.0, "0.05 m from a wall"),
    (9.0, 2.0, "is outside every room"),
])
def test_a_robot_that_does_not_fit_is_a_world_error(x: float, y: float, expected: str) -> None:
    with pytest.raises(WorldError, match=r"robot\.pose") as error:
        _world(x, y)
    assert expected in str(error.value)
    assert str(error.value).startswith("tiny.yaml: line 10: robot.pose: ")


@pytest.mark.parametrize(("x", "y"), [(2.0, 2.0), (4.0, 2.0), (6.8, 1.0), (0.3, 0.3)])
def test_free_floor_and_door_openings_fit(x: float, y: float) -> None:
    assert _world(x, y).footprint_problem(x, y) is None


def test_a_smaller_radius_fits_closer() -> None:
    world = _world(2.0, 2.0)
    assert world.footprint_problem(6.6, 2.0) is not None
    assert world.footprint_problem(6.6, 2.0, radius=0.05) is None
