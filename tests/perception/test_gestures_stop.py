"""A stop gesture stops the embodied robot that guides or follows the person showing it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.app import Fidelity, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.perception.gestures import classify_gesture
from homebot.robot import Blocker
from homebot.sim.keypoints import gesture_keypoints
from homebot.world import World

pytest.importorskip("cv2")


def test_guiding_stops_within_a_second_of_the_persons_stop_gesture(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(
        world=apartment, seed=0, navigator=apartment_navigator, fidelity=Fidelity.EMBODIED))
    robot, simulation = run.robot, run.simulation
    rng = np.random.default_rng(0)
    started = robot.now()
    shown: list[float] = []

    def stop_shown(person: str) -> bool:
        # the person's arm, seen by the robot: a stop gesture from 3 s into the drive
        here = simulation.robot_pose[:2]
        behind = (here[0] - 0.8, here[1])
        gesture = "stop" if robot.now() - started > 3.0 else "none"
        seen = classify_gesture(gesture_keypoints(gesture, behind, here, rng, seconds=0.5),
                                here) == "stop"
        if seen and not shown:
            shown.append(robot.now())
        return person == "Alex" and seen

    robot.stop_shown = stop_shown
    goal = apartment.placements["bed"].approach
    report = robot.move_to(goal, escort="Alex")
    assert not report.reached and report.blocker is Blocker.STOPPED
    assert report.person == "Alex"
    assert shown and robot.now() - shown[0] < 1.0
    assert math.dist(simulation.robot_pose[:2], goal.xy()) > 1.0
