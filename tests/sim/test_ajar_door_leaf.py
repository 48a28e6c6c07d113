"""A door left half open (``opening`` in the world file): the simulator's laser and bumper
meet its leaf where it stands, and a door without one is as it always was."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import Point

from homebot.errors import WorldError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import Twist
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.geometry import TrueGeometry
from homebot.world import DoorState, LaserModel, World

_TWO_ROOMS = """
name: ajar_door
rooms:
  - {{name: hall, polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]}}
  - {{name: room, polygon: [[0, 3], [4, 3], [4, 6], [0, 6]]}}
doors:
  - {{name: door, rooms: [hall, room], position: [2, 3], width: 0.8{door}}}
robot:
  pose: [2, 1.5, 1.5708]
"""
_AJAR = ", opening: 60, hinge: west, swings_into: room"


def _world(door: str = _AJAR) -> World:
    return World.from_yaml_text(_TWO_ROOMS.format(door=door))


def _body(world: World) -> SimBody:
    return SimBody(Simulation(world, seed=1, navigator=Navigator(world)),
                   laser=LaserModel(noise=0.0))


def test_the_leaf_stands_at_its_opening_from_the_hinge() -> None:
    leaf = _world().door_leaf("door")
    assert leaf is not None
    # hinged at the west jamb (1.6, 3), 0.8 m long, 60 degrees from the wall into the room
    tip = (1.6 + 0.8 * math.cos(math.radians(60)), 3 + 0.8 * math.sin(math.radians(60)))
    assert leaf.distance(Point(1.6, 3.0)) < 1e-9 and leaf.distance(Point(*tip)) < 1e-9
    assert leaf.distance(Point(2.3, 3.3)) > 0.2  # the far side of the doorway is free
    assert _world("").door_leaf("door") is None


def test_the_laser_meets_the_leaf_where_it_stands() -> None:
    body = _body(_world())
    # from below the doorway's west half, looking north: the leaf, not the far wall
    body.teleport(Pose(1.75, 2.0, math.pi / 2))
    ahead = len(body.scan().ranges) // 2
    assert 1.0 < body.scan().ranges[ahead] < 1.5
    # through the free east half the beam reaches the room's far wall
    body.teleport(Pose(2.25, 2.0, math.pi / 2))
    assert body.scan().ranges[ahead] > 3.5
    # the same world with the leaf flat against the wall: both beams go through
    flat = _body(_world(""))
    flat.teleport(Pose(1.75, 2.0, math.pi / 2))
    assert flat.scan().ranges[ahead] > 3.5


def test_the_bumper_stops_the_base_at_the_leaf() -> None:
    body = _body(_world())
    body.teleport(Pose(1.75, 2.5, math.pi / 2))
    body.command_velocity(Twist(0.4, 0.0, 0.0))
    body.tick(100)
    assert [c["with"] for c in body.sim.collisions] == ["wall or furniture"]
    assert body.sim.robot_pose[1] < 3.0


def test_a_shut_door_has_its_leaf_in_the_doorway_not_at_its_opening() -> None:
    world = _world()
    geometry = TrueGeometry.of(world)
    shut = frozenset({"door"})
    assert geometry.clearance(2.3, 3.0, shut) == pytest.approx(0.0, abs=0.06)
    assert geometry.clearance(1.8, 3.3, shut) > geometry.clearance(1.8, 3.3, frozenset())


def test_a_world_without_openings_has_the_geometry_it_always_had() -> None:
    world = _world("")
    geometry = TrueGeometry.of(world)
    expected = geometry.raster.occupied.astype(np.uint8)
    assert np.array_equal(geometry.solid_image(frozenset()), expected)
    assert world.doors["door"].state is DoorState.OPEN


@pytest.mark.parametrize(("door", "field", "fix"), [
    (", opening: 60, hinge: north", "doors.0.hinge", "use east or west"),
    (", opening: 60, swings_into: kitchen", "doors.0.swings_into", "use 'hall' or 'room'"),
    (", hinge: west", "doors.0", "give the door an opening too"),
    (", opening: 190", "doors.0.opening", "less than or equal to 180"),
])
def test_a_leaf_written_wrong_is_named_with_its_field(door: str, field: str, fix: str) -> None:
    with pytest.raises(WorldError) as error:
        _world(door)
    assert field in str(error.value) and fix in str(error.value)


def test_a_door_opened_wide_has_its_leaf_swung_back_against_the_wall() -> None:
    world = _world(", opening: 15, hinge: west, swings_into: room")
    body = _body(world)
    # looking north through the middle of the doorway: the leaf, barely ajar
    body.teleport(Pose(2.0, 2.0, math.pi / 2))
    ahead = len(body.scan().ranges) // 2
    assert body.scan().ranges[ahead] < 1.5
    body.sim.open_wide("door")
    body.tick()
    assert body.scan().ranges[ahead] > 3.5  # on to the room's far wall
    assert body.sim.door_state["door"] is DoorState.OPEN
    # and the bumper no longer meets it in the doorway
    assert TrueGeometry.of(world).clearance(2.0, 3.0, frozenset(), frozenset({"door"})) > 0.3
    assert TrueGeometry.of(world).clearance(2.0, 3.0, frozenset()) < 0.1
