"""Gestures from arm keypoints: which gesture, and what a pointing ray meets."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.geometry import Ray
from homebot.perception.gestures import (
    Surface,
    classify_gesture,
    person_gesture,
    pointed_object,
    pointed_target,
    pointing_ray,
)
from homebot.sim.keypoints import GESTURES, gesture_keypoints

ROBOT = (2.0, 0.0)
SURFACES = {
    "table": Surface((0.0, 3.0), (1.2, 0.8), 0.75),
    "shelf": Surface((3.0, 3.0), (0.8, 0.4), 1.2),
    "bed": Surface((-3.0, 0.0), (2.0, 1.6), 0.5),
}


@pytest.mark.parametrize("gesture", GESTURES)
def test_each_gesture_is_told_apart(gesture: str) -> None:
    rng = np.random.default_rng(3)
    for _ in range(10):
        frames = gesture_keypoints(gesture, (0.0, 0.0), ROBOT, rng, target=(0.0, 3.0, 0.75))
        assert classify_gesture(frames, ROBOT) == gesture


@pytest.mark.parametrize(("gesture", "side", "named"), [
    ("raising", "left", "raising_left_arm"), ("raising", "right", "raising_right_arm"),
    ("pointing", "left", "pointing_left"), ("pointing", "right", "pointing_right")])
def test_left_and_right_are_the_persons_own(gesture: str, side: str, named: str) -> None:
    rng = np.random.default_rng(5)
    for _ in range(10):
        person = tuple(rng.uniform(-3.0, 3.0, 2))
        facing = math.atan2(ROBOT[1] - person[1], ROBOT[0] - person[0])
        # facing the robot, a person's left is counter-clockwise of the line to it
        turn = math.pi / 2 if side == "left" else -math.pi / 2
        target = (person[0] + 2 * math.cos(facing + turn),
                  person[1] + 2 * math.sin(facing + turn), 0.75)
        frames = gesture_keypoints(gesture, person, ROBOT, rng, target=target, side=side,
                                   height=float(rng.uniform(1.55, 1.95)))
        assert person_gesture(frames, ROBOT) == named


@pytest.mark.parametrize("target", sorted(SURFACES))
def test_pointing_picks_the_placement_pointed_at(target: str) -> None:
    rng = np.random.default_rng(4)
    surface = SURFACES[target]
    for _ in range(10):
        frames = gesture_keypoints("pointing", (0.0, 0.0), ROBOT, rng,
                                   target=(*surface.center, surface.height))
        gesture = pointing_ray(frames)
        assert isinstance(gesture, Ray)
        assert pointed_target(gesture, SURFACES) == target


def test_pointing_up_at_nothing_meets_no_placement() -> None:
    gesture = Ray((0.0, 0.0, 1.6), (0.0, -0.5, 2.0))
    assert pointed_target(gesture, SURFACES) is None


def test_that_one_is_the_object_nearest_the_ray() -> None:
    gesture = Ray((0.0, 0.0, 1.6), (0.0, 0.5, 1.45))
    ray = np.array([0.0, 0.5, -0.15]) / math.hypot(0.5, 0.15)
    on_ray = tuple(np.array([0.0, 0.0, 1.6]) + 3.0 * ray)
    objects = {"red cup": (on_ray[0] + 0.05, on_ray[1], on_ray[2]),
               "blue cup": (on_ray[0] + 0.6, on_ray[1], on_ray[2])}
    assert pointed_object(gesture, objects) == "red cup"
    assert pointed_object(gesture, {"far": (3.0, 0.0, 0.0)}) is None
