"""way_through: the straight way a 0.5 m robot takes through a 0.8 m doorway, past a leaf
left half open (either way), furniture by a jamb or someone in it, from laser sweeps cast
in a small plan of two rooms (``test_door_seen_open_homes``'s)."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import LineString, Point, box
from test_door_seen_open_homes import _CENTRE, _NORMAL, _WIDTH, _leaf, _sweep

from homebot.embodied.doors import WayThrough, door_seen_open, way_through
from homebot.geometry import Pose, from_frame
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.world import World

_RADIUS = 0.25
_FACING = Pose(0.0, -0.6, math.pi / 2)  # stopped 0.6 m before the door, facing it


def _way(pose: Pose, *extra: object) -> WayThrough | None:
    scan = _sweep(pose, *extra)
    return way_through(from_frame(pose, scan.points()), _CENTRE, _NORMAL, _WIDTH, 0.1,
                       _RADIUS)


def _leaf_towards_the_robot(opening_deg: float) -> object:
    """The leaf hinged at the right jamb, swung ``opening_deg`` into the robot's room."""
    angle = math.radians(opening_deg)
    hinge = (_WIDTH / 2, 0.0)
    tip = (hinge[0] - _WIDTH * math.cos(angle), hinge[1] - _WIDTH * math.sin(angle))
    return LineString([hinge, tip]).buffer(0.02)


def test_an_open_doorway_is_crossed_straight() -> None:
    way = _way(_FACING)
    assert way is not None and way.slant == 0.0 and way.room > 0.1
    assert way.entry[1] < 0 < way.exit[1]  # from the robot's side to the far one


@pytest.mark.parametrize("opening_deg", [55.0, 60.0, 75.0])
def test_past_a_half_open_leaf_the_way_runs_along_it(opening_deg: float) -> None:
    way = _way(_FACING, _leaf(opening_deg))
    assert way is not None
    # slanted as the leaf stands (the way parallel to it, give or take the 5-degree steps)
    assert abs(abs(way.slant) - math.radians(90.0 - opening_deg)) <= math.radians(10.0)
    assert door_seen_open(_sweep(_FACING, _leaf(opening_deg)), _FACING, _CENTRE, _NORMAL,
                          _WIDTH) is True


@pytest.mark.parametrize("pose", [_FACING, Pose(0.5, -1.2, 2.0),
                                  Pose(0.29, -1.01, 2.16)])  # behind the leaf's face
def test_a_leaf_half_open_towards_the_robot_is_not_read_shut_and_passable(pose: Pose) -> None:
    leaf = _leaf_towards_the_robot(60.0)
    assert door_seen_open(_sweep(pose, leaf), pose, _CENTRE, _NORMAL, _WIDTH) is not False
    assert _way(pose, leaf) is not None


def test_furniture_a_little_beside_the_doorway_leaves_a_way() -> None:
    cabinet = box(0.45, -0.6, 1.25, -0.2)
    assert _way(_FACING, cabinet) is not None
    assert door_seen_open(_sweep(_FACING, cabinet), _FACING, _CENTRE, _NORMAL, _WIDTH) is True


def test_someone_standing_in_the_doorway_leaves_none() -> None:
    legs = [Point(-0.1, 0.0).buffer(0.06), Point(0.12, 0.02).buffer(0.06)]
    assert _way(_FACING, *legs) is None


def test_a_leaf_barely_ajar_leaves_none() -> None:
    assert _way(_FACING, _leaf(25.0)) is None


_LANDING = """
name: landing_and_kitchen
rooms:
  - {name: landing, polygon: [[3, 2.5], [5.5, 2.5], [5.5, 4.5], [3, 4.5]]}
  - {name: kitchen, polygon: [[0, 0], [3, 0], [3, 4.5], [0, 4.5]]}
doors:
  - {name: kitchen door, rooms: [kitchen, landing], position: [3, 3.5], width: 0.8,
     opening: 60, hinge: north, swings_into: landing}
placements:
  - {name: console, category: table, room: landing, center: [3.55, 4.3], size: [0.8, 0.3]}
robot:
  pose: [4.2, 3.5, 3.14]
"""


@pytest.mark.parametrize("pose", [Pose(4.01, 3.79, -2.55), Pose(4.2, 3.5, math.pi),
                                  Pose(3.7, 3.1, 2.6)])
def test_a_leaf_swung_towards_the_robot_in_front_of_the_doorway_is_not_read_shut(
        pose: Pose) -> None:
    # by the simulator's laser: behind the leaf's face (the first pose), the doorway is
    # hidden by a leaf that stands across it at a slant, as no shut door does
    world = World.from_yaml_text(_LANDING)
    body = SimBody(Simulation(world, seed=1, navigator=Navigator(world)))
    body.teleport(pose)
    door = world.doors["kitchen door"]
    assert door_seen_open(body.scan(), pose, door.position, (1.0, 0.0), door.width) is True
