"""Gestures from the head camera's depth: arms drawn by the simulator, segmented by the robot."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.geometry import Pose
from homebot.perception.body_parts import arm_track, body_parts, looking_tilt
from homebot.perception.gestures import gesture_from_depth
from homebot.robot import Body, HeadState, RgbdFrame
from homebot.sim.body import SimBody
from homebot.sim.body_tracker import PeopleArms, person_solids
from homebot.sim.camera import CameraSimulator, Limb, SceneGeometry
from homebot.sim.keypoints import ArmMotion, draw_motion
from homebot.world import PersonModel, Posture, World

PERSON = (3.0, 3.0)  #: a free spot in the apartment's living room
ROBOT = (5.0, 3.4, math.atan2(3.0 - 3.4, 3.0 - 5.0))  #: 2 m off, facing the person
HEIGHT = 1.75


def _burst(apartment: World, motion: ArmMotion, *, noise: bool = True,
           frames: int = 10) -> list[RgbdFrame]:
    camera = CameraSimulator(SceneGeometry.of(apartment), np.random.default_rng(7), noise=noise)
    model = PersonModel(name="Pat", room="living room", position=PERSON, height=HEIGHT,
                        clothes=["red sweater", "blue jeans"])
    arms = PeopleArms(0)
    arms.gestures["Pat"] = motion
    facing = math.atan2(ROBOT[1] - PERSON[1], ROBOT[0] - PERSON[0])
    body = person_solids(apartment, "Pat", model, Posture.STANDING, PERSON, facing)
    head = HeadState(0.0, looking_tilt(math.dist(PERSON, ROBOT[:2]), camera.intrinsics))
    return [camera.render(t, ROBOT, head, [*body, *arms.solids(
        "Pat", model, Posture.STANDING, PERSON, ROBOT[:2], t)])
        for t in np.arange(frames) * 0.1]


def _side_target(side: str) -> tuple[float, float, float]:
    facing = math.atan2(ROBOT[1] - PERSON[1], ROBOT[0] - PERSON[0])
    turn = -math.pi / 2 if side == "right" else math.pi / 2
    return (PERSON[0] + 2 * math.cos(facing + turn), PERSON[1] + 2 * math.sin(facing + turn),
            0.75)


def test_a_limb_is_drawn_at_its_place_in_the_depth_image(apartment: World) -> None:
    camera = CameraSimulator(SceneGeometry.of(apartment), np.random.default_rng(0),
                             noise=False)
    # a level arm across the view, 2 m ahead of a robot facing +x at (1, 3)
    limb = Limb((3.0, 2.8, 1.3), (3.0, 3.2, 1.3), 0.05, (200, 0, 0))
    frame = camera.render(0.0, (1.0, 3.0, 0.0), HeadState(), [limb])
    k = frame.intrinsics
    assert frame.depth[round(k.cy), round(k.cx)] == pytest.approx(1.95, abs=0.005)
    assert int(frame.rgb[round(k.cy), round(k.cx), 0]) > 100  # the limb's red
    # beyond its end the ray goes on to the wall behind
    beyond = round(k.cx - k.fx * 0.3 / 2.0)
    assert frame.depth[round(k.cy), beyond] > 2.5


def test_the_arm_keypoints_are_found_near_the_true_ones(apartment: World) -> None:
    motion = draw_motion("pointing", np.random.default_rng(1), target=_side_target("right"),
                         side="right", height=HEIGHT)
    frames = _burst(apartment, motion, frames=3)
    truth = motion.at(PERSON, ROBOT[:2], np.zeros(1))[0]
    pose = Pose(*ROBOT)
    parts = body_parts(frames[0], pose, (PERSON[0] + 0.08, PERSON[1] - 0.05))
    assert parts is not None
    assert set(parts.arms) == {"right"}  # the left arm hangs by the trunk
    head, shoulder, _, hand = parts.keypoints("right")
    assert math.dist(head, truth[0]) < 0.05
    assert math.dist(shoulder, truth[1]) < 0.06
    assert math.dist(hand, truth[3]) < 0.06


@pytest.mark.parametrize(("gesture", "side", "named"), [
    ("pointing", "left", "pointing_left"), ("pointing", "right", "pointing_right"),
    ("raising", "left", "raising_left_arm"), ("raising", "right", "raising_right_arm"),
    ("waving", "left", "waving"), ("stop", "right", "stop"), ("none", "right", "none")])
def test_each_gesture_is_named_from_the_depth_frames(apartment: World, gesture: str, side: str,
                                                     named: str) -> None:
    motion = draw_motion(gesture, np.random.default_rng(2), target=_side_target(side),
                         side=side, height=HEIGHT)
    frames = _burst(apartment, motion)
    assert gesture_from_depth(frames, [Pose(*ROBOT)] * len(frames), PERSON) == named


def test_nobody_where_the_person_was_said_to_be_is_no_gesture(apartment: World) -> None:
    motion = draw_motion("waving", np.random.default_rng(3), height=HEIGHT)
    frames = _burst(apartment, motion, frames=3)
    elsewhere = (PERSON[0], PERSON[1] + 2.5)
    assert arm_track(frames, [Pose(*ROBOT)] * 3, elsewhere) is None
    assert gesture_from_depth(frames, [Pose(*ROBOT)] * 3, elsewhere) == "none"
    with pytest.raises(ValueError, match="one pose a frame"):
        arm_track(frames, [Pose(*ROBOT)], PERSON)


def test_the_body_port_carries_no_gesture() -> None:
    # the robot learns what people do only from the camera's frames
    for port in (Body, SimBody):
        assert not hasattr(port, "person_view")


def test_the_depth_gesture_figures_judge_by_the_gesture_made() -> None:
    from homebot.trials.people import depth_gesture_figures

    figures = depth_gesture_figures(5, trials=3)
    assert sum(sum(read.values()) for read in figures["read_as"].values()) == 15
    # three looks at each gesture: at most one missed of each
    assert all(share >= 2 / 3 for share in figures["right"].values()), figures


@pytest.mark.parametrize("motion", ["circle", "swipe_right", "swipe_left"])
def test_a_dynamic_gesture_is_read_from_the_hands_path(apartment: World, motion: str) -> None:
    from homebot.perception.strokes import StrokeRecogniser

    drawn = draw_motion(motion, np.random.default_rng(6), side="right", height=HEIGHT)
    frames = _burst(apartment, drawn, frames=30)
    track = arm_track(frames, [Pose(*ROBOT)] * len(frames), PERSON)
    assert track is not None
    assert StrokeRecogniser().read(track, ROBOT[:2]) == motion
