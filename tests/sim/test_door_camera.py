"""The head camera sees a shut door's leaf and handle (sim/camera.py ``door_solids``), and
the robot's door perception finds the hinge from that frame (perception/door_leaf.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.perception.door_leaf import perceive_door
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.world import DoorState, World

_TWO_ROOMS = """
name: shut_door
rooms:
  - {{name: hall, polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]}}
  - {{name: room, polygon: [[0, 3], [4, 3], [4, 6], [0, 6]]}}
doors:
  - {{name: door, rooms: [hall, room], position: [2, 3], width: 0.8, state: closed{hinge}}}
robot:
  pose: [2, 1.8, 1.5708]
"""


def _body(hinge: str = "") -> SimBody:
    world = World.from_yaml_text(_TWO_ROOMS.format(hinge=hinge))
    body = SimBody(Simulation(world, seed=2, navigator=Navigator(world)))
    body.teleport(Pose(2.0, 1.8, math.pi / 2))
    body.point_head(0.0, 0.2)
    return body


def test_the_hinge_is_found_from_the_head_camera() -> None:
    body = _body()
    points, _ = body.camera().points()
    seen = perceive_door(points, np.random.default_rng(0))
    assert seen is not None
    # base frame: x north, y west; the default hinge is the west jamb (1.6, 3)
    assert np.linalg.norm(seen.hinge - (1.18, 0.39)) < 0.05
    assert np.linalg.norm(seen.latch - (1.18, -0.39)) < 0.05
    assert seen.handle[1] < -0.2 and seen.handle[2] == pytest.approx(1.05, abs=0.03)


def test_an_east_hinge_puts_the_handle_west() -> None:
    body = _body(", opening: 60, hinge: east")
    seen = perceive_door(body.camera().points()[0], np.random.default_rng(0))
    assert seen is not None
    assert seen.hinge[1] < -0.3 and seen.handle[1] > 0.2


def test_an_open_door_shows_no_leaf() -> None:
    body = _body()
    body.sim.door_state["door"] = DoorState.OPEN
    assert perceive_door(body.camera().points()[0], np.random.default_rng(0)) is None
