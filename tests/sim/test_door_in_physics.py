"""A shut door's leaf in the arm's physics (sim/arm.py ``DoorLeaf``, sim/hands.py): latched
until a lever is pressed, locked for good when the door is, and open in the simulator's
truth only once physics has swung it past ``DOOR_SWUNG_OPEN``."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("mujoco")

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.world import DoorState, World

_TWO_ROOMS = """
name: shut_door
rooms:
  - {{name: hall, polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]}}
  - {{name: room, polygon: [[0, 3], [4, 3], [4, 6], [0, 6]]}}
doors:
  - {{name: door, rooms: [hall, room], position: [2, 3], width: 0.8, state: {state}}}
robot:
  pose: [2, 1.8, 1.5708]
"""


def _at_the_door(state: str = "closed", standing: float = 1.9) -> SimBody:
    world = World.from_yaml_text(_TWO_ROOMS.format(state=state))
    body = SimBody(Simulation(world, seed=2, navigator=Navigator(world)))
    body.teleport(Pose(2.0, standing, math.pi / 2))
    return body


def _press_levers(body: SimBody) -> None:
    sim = body.hands.driver().sim
    for k in range(2):
        sim.data.xfrc_applied[sim.model.body(f"door:door:lever{k}").id, :3] = (0.0, 0.0, -30.0)


def _pull_leaf(body: SimBody, newtons: float) -> None:
    sim = body.hands.driver().sim
    sim.data.xfrc_applied[sim.model.body("door:door").id, :3] = (0.0, -newtons, 0.0)


def test_a_latched_leaf_holds_until_a_lever_is_pressed_then_swings_open() -> None:
    body = _at_the_door()
    sim = body.hands.driver().sim
    assert sim.doors["door"].swing == -1.0  # into the hall, the first room: towards the robot
    _pull_leaf(body, 40.0)
    body.tick(10)
    assert sim.door_angle("door") < 0.01 and body.sim.door_state["door"] is DoorState.CLOSED
    _press_levers(body)
    body.tick(4)
    assert not sim.latched["door"]
    body.tick(20)
    assert sim.door_angle("door") > 0.1
    body.tick(60)
    assert sim.door_angle("door") >= 1.2
    assert body.sim.door_state["door"] is DoorState.OPEN


def test_a_locked_door_does_not_open_for_its_lever() -> None:
    body = _at_the_door("locked")
    sim = body.hands.driver().sim
    _press_levers(body)
    _pull_leaf(body, 40.0)
    body.tick(40)
    assert sim.latched["door"] and sim.door_angle("door") < 0.01
    assert body.sim.door_state["door"] is DoorState.LOCKED


def test_the_leaf_swinging_into_the_robot_is_a_collision() -> None:
    body = _at_the_door(standing=2.3)
    _press_levers(body)
    _pull_leaf(body, 40.0)
    body.tick(40)
    hits = [c for c in body.sim.collisions if c["with"] == "door door"]
    assert len(hits) == 1 and "base" in hits[0]["by"]
