"""homebot.geometry: angle wrapping, pose composition and its inverse, quaternions, rays."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from homebot.geometry import (
    Pose,
    Ray,
    from_frame,
    nearest_by_angle,
    quaternion_from_yaw,
    rays_cross_line,
    to_frame,
    wrap_angle,
    wrap_angles,
    yaw_from_quaternion,
    yaw_rotation,
)

angles = st.floats(min_value=-50.0, max_value=50.0, allow_nan=False)
coordinates = st.floats(min_value=-100.0, max_value=100.0, allow_nan=False)
poses = st.builds(Pose, coordinates, coordinates, angles)


def _same_pose(a: Pose, b: Pose, tolerance: float = 1e-7) -> bool:
    return (math.isclose(a.x, b.x, abs_tol=tolerance) and math.isclose(a.y, b.y, abs_tol=tolerance)
            and abs(wrap_angle(a.theta - b.theta)) < tolerance)


# ------------------------------------------------------------------ angles


@given(angles)
def test_a_wrapped_angle_lies_in_one_turn_and_points_the_same_way(angle: float) -> None:
    wrapped = wrap_angle(angle)
    assert -math.pi <= wrapped < math.pi
    assert math.isclose(math.cos(wrapped), math.cos(angle), abs_tol=1e-9)
    assert math.isclose(math.sin(wrapped), math.sin(angle), abs_tol=1e-9)


def test_wrapping_keeps_small_angles_and_folds_large_ones() -> None:
    assert wrap_angle(0.5) == 0.5
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap_angle(-7.0) == pytest.approx(-7.0 + 2 * math.pi)


@given(st.lists(angles, min_size=1, max_size=20))
def test_arrays_wrap_as_single_angles_do(values: list[float]) -> None:
    assert wrap_angles(values).tolist() == [wrap_angle(value) for value in values]


@given(angles)
def test_the_yaw_quaternion_round_trips(yaw: float) -> None:
    w, x, y, z = quaternion_from_yaw(yaw)
    assert math.isclose(w * w + x * x + y * y + z * z, 1.0)
    assert abs(wrap_angle(yaw_from_quaternion(w, x, y, z) - yaw)) < 1e-9


def test_a_quarter_turn_is_the_textbook_quaternion() -> None:
    w, x, y, z = quaternion_from_yaw(math.pi / 2)
    assert (w, x, y, z) == pytest.approx((math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)))
    # a quaternion turned about x as well still gives its heading
    roll = (math.cos(0.2), math.sin(0.2), 0.0, 0.0)
    assert yaw_from_quaternion(*roll) == pytest.approx(0.0)


@given(angles)
def test_the_yaw_rotation_turns_as_the_pose_does(yaw: float) -> None:
    rotation = yaw_rotation(yaw)
    assert np.allclose(rotation @ rotation.T, np.eye(3))
    x, y = Pose(0.0, 0.0, yaw).apply(1.0, 2.0)
    assert np.allclose(rotation @ (1.0, 2.0, 3.0), (x, y, 3.0))


# ------------------------------------------------------------------ poses and frames


def test_a_pose_stays_frozen_hashable_and_gives_its_position() -> None:
    pose = Pose(1.0, 2.0, 0.5)
    assert pose.xy() == (1.0, 2.0)
    assert Pose(1.0, 2.0).theta == 0.0
    assert {pose: "here"}[Pose(1.0, 2.0, 0.5)] == "here"
    with pytest.raises(AttributeError):
        pose.x = 3.0  # type: ignore[misc]


def test_composition_moves_forward_along_the_heading() -> None:
    robot = Pose(1.0, 1.0, math.pi / 2)
    assert _same_pose(robot.compose(Pose(2.0, 0.0)), Pose(1.0, 3.0, math.pi / 2))
    assert _same_pose(robot.compose(Pose(0.0, 1.0, math.pi)), Pose(0.0, 1.0, -math.pi / 2))
    assert robot.apply(2.0, 0.0) == pytest.approx((1.0, 3.0))


@given(poses, poses)
def test_relative_to_undoes_compose(frame: Pose, local: Pose) -> None:
    assert _same_pose(frame.compose(local).relative_to(frame), local, 1e-6)
    assert _same_pose(frame.compose(local.relative_to(frame)), local, 1e-6)


@given(poses)
def test_a_pose_composed_with_its_inverse_is_the_origin(pose: Pose) -> None:
    assert _same_pose(pose.compose(pose.inverse()), Pose(0.0, 0.0), 1e-6)
    assert _same_pose(pose.inverse().compose(pose), Pose(0.0, 0.0), 1e-6)


@given(poses, poses, poses)
def test_composition_is_associative(a: Pose, b: Pose, c: Pose) -> None:
    assert _same_pose(a.compose(b).compose(c), a.compose(b.compose(c)), 1e-6)


@given(poses, st.lists(st.tuples(coordinates, coordinates, coordinates), min_size=1,
                       max_size=10))
def test_points_go_into_a_frame_and_back(frame: Pose, points: list[tuple[float, ...]]) -> None:
    array = np.array(points)
    seen = to_frame(frame, array)
    assert seen[:, 2].tolist() == array[:, 2].tolist()  # a height stays as it is
    assert np.allclose(from_frame(frame, seen), array, atol=1e-6)
    for point, moved in zip(array, from_frame(frame, array), strict=True):
        assert moved[:2] == pytest.approx(frame.apply(point[0], point[1]))


# ------------------------------------------------------------------ rays


def test_the_ray_from_shoulder_through_hand_meets_the_table() -> None:
    met = Ray((1.0, 0.15, 1.4), (0.7, 0.15, 1.2)).meets_height(0.75)
    assert met is not None
    x, y, along = met
    assert x == pytest.approx(0.025) and y == pytest.approx(0.15)
    assert along == pytest.approx(math.dist((1.0, 0.15, 1.4), (0.025, 0.15, 0.75)))
    assert Ray((0, 0, 1.4), (0.3, 0, 1.6)).meets_height(0.75) is None  # pointing up
    assert Ray((0, 0, 0.5), (0.3, 0, 0.4)).meets_height(0.75) is None  # the plane is behind


@given(st.tuples(coordinates, coordinates, st.floats(0.5, 2.0)),
       st.tuples(coordinates, coordinates), st.floats(0.0, 0.4))
def test_a_ray_aimed_at_a_point_of_a_plane_meets_it_there(
        origin: tuple[float, float, float], target: tuple[float, float], height: float) -> None:
    aim = (target[0], target[1], height)
    hand = tuple(o + 0.3 * (a - o) for o, a in zip(origin, aim, strict=True))
    met = Ray(origin, (hand[0], hand[1], hand[2])).meets_height(height)
    assert met is not None
    assert met[:2] == pytest.approx(target, abs=1e-6)


def test_pointing_picks_the_point_nearest_the_ray_within_reach() -> None:
    ray = Ray((0.0, 0.0, 1.5), (1.0, 0.0, 1.5))
    points = {"ahead": (5.0, 0.2, 1.5), "beside": (5.0, 2.0, 1.5), "behind": (-5.0, 0.0, 1.5)}
    assert ray.angle_to((5.0, 0.0, 1.5)) == pytest.approx(0.0)
    assert ray.angle_to((-5.0, 0.0, 1.5)) == pytest.approx(math.pi)
    assert ray.angle_to((0.0, 0.0, 1.5)) is None
    assert nearest_by_angle(ray, points, math.radians(8.0)) == "ahead"
    assert nearest_by_angle(ray, {"beside": points["beside"]}, math.radians(8.0)) is None


def test_beams_cross_a_doorway_line_where_they_meet_it() -> None:
    # a wall along y at x = 2 (normal +x); beams from the origin at 0°, 45° and 90°
    directions = np.array([[1.0, 0.0], [math.sqrt(0.5), math.sqrt(0.5)], [0.0, 1.0]])
    distance, offset = rays_cross_line((0.0, 0.0), directions, (2.0, 0.0), (1.0, 0.0))
    assert distance[:2] == pytest.approx([2.0, 2.0 * math.sqrt(2.0)])
    assert offset[:2] == pytest.approx([0.0, 2.0])
    assert not np.isfinite(distance[2])  # along the wall: never crosses
