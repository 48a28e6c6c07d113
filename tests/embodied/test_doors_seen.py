"""Whether a door is open, told by the embodied robot's laser alone."""

from __future__ import annotations

import math

import pytest

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.world import DoorState, World

pytest.importorskip("cv2")

DOOR = "bedroom door"


def _robot_before_the_door(world: World, navigator: Navigator, distance: float
                           ) -> Run:
    run = build_run(RunSettings(
        world=world, seed=0, navigator=navigator, fidelity=Fidelity.EMBODIED))
    door = world.doors[DOOR]
    pose = world.point_before_door(DOOR, door.rooms[0], distance)
    run.simulation.robot_pose = (pose.x, pose.y, pose.theta)
    run.robot.localisation.initialise(pose, spread=0.01, angle_spread=0.01)  # type: ignore[attr-defined]
    return run


@pytest.mark.parametrize("distance", [0.6, 1.5, 2.5])
def test_a_shut_door_is_seen_shut_and_an_open_one_open(
        apartment: World, apartment_navigator: Navigator, distance: float) -> None:
    run = _robot_before_the_door(apartment, apartment_navigator, distance)
    assert run.robot.door_is_open(DOOR) is True
    run.simulation.door_state[DOOR] = DoorState.CLOSED
    assert run.robot.door_is_open(DOOR) is False


def test_someone_in_an_open_doorway_does_not_shut_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _robot_before_the_door(apartment, apartment_navigator, 1.2)
    run.simulation.place_person_in_doorway(DOOR)
    assert run.robot.door_is_open(DOOR) is True


@pytest.mark.parametrize("state", [DoorState.OPEN, DoorState.CLOSED])
def test_a_door_behind_the_robot_is_turned_to_and_read(
        apartment: World, apartment_navigator: Navigator, state: DoorState) -> None:
    run = _robot_before_the_door(apartment, apartment_navigator, 1.0)
    run.simulation.door_state[DOOR] = state
    here = run.simulation.robot_pose
    turned = Pose(here[0], here[1], here[2] + math.pi)  # the door is in the laser's blind spot
    run.simulation.robot_pose = (turned.x, turned.y, turned.theta)
    run.robot.localisation.initialise(turned, spread=0.01, angle_spread=0.01)  # type: ignore[attr-defined]
    assert run.robot.door_is_open(DOOR) is (state is DoorState.OPEN)
    door = apartment.doors[DOOR].position
    x, y, theta = run.simulation.robot_pose
    bearing = math.atan2(door[1] - y, door[0] - x)
    assert abs(math.remainder(bearing - theta, math.tau)) < 0.5  # it turned to face the door
