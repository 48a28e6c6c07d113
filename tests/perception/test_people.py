"""People from the laser: leg segments, pairing, the Kalman/Hungarian tracker, posture, clothes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.geometry import Pose
from homebot.perception.people import (
    COLOURS,
    PeopleTracker,
    clothes_colour,
    detect_legs,
    pair_legs,
    posture_from_profile,
    segment_scan,
)
from homebot.robot import LaserScan
from homebot.sim.crowd import crowd_scene
from homebot.sim.silhouettes import POSTURES, person_cloud, torso_patch


def _scan(ranges: np.ndarray, fov: float = math.radians(270)) -> LaserScan:
    return LaserScan(0.0, -fov / 2, fov / (len(ranges) - 1), 0.05, 30.0, ranges)


def _cast(circles: list[tuple[float, float, float]], wall: float = 5.0,
          beams: int = 1081) -> LaserScan:
    """A scan of circles in front of a straight wall ``wall`` metres ahead."""
    fov = math.radians(270)
    angles = -fov / 2 + fov / (beams - 1) * np.arange(beams)
    cos = np.cos(angles)
    ranges = np.where(cos > 1e-3, wall / np.maximum(cos, 1e-3), np.inf)
    ranges[ranges > 30] = np.inf
    directions = np.column_stack((cos, np.sin(angles)))
    for x, y, r in circles:
        along = directions @ np.array([x, y])
        squared = x * x + y * y - along ** 2
        inside = (squared <= r * r) & (along > 0)
        hit = along - np.sqrt(np.where(inside, r * r - squared, 0.0))
        ranges = np.where(inside & (hit < ranges), hit, ranges)
    return _scan(ranges)


def test_segments_break_where_ranges_jump() -> None:
    ranges = np.array([2.0, 2.0, 2.01, 4.0, 4.0, np.inf, 4.0, 4.01])
    segments = segment_scan(_scan(ranges))
    assert [list(s) for s in segments] == [[0, 1, 2], [3, 4], [6, 7]]


def test_two_legs_in_front_of_a_wall_are_found_and_the_wall_is_not() -> None:
    scan = _cast([(2.0, 0.1, 0.06), (2.0, -0.15, 0.06)])
    legs = detect_legs(scan)
    assert len(legs) == 2
    for truth in ((2.0, 0.1), (2.0, -0.15)):
        assert min(math.dist(truth, tuple(leg)) for leg in legs) < 0.05
    assert len(detect_legs(_cast([]))) == 0


def test_thin_posts_and_wide_boxes_are_not_legs() -> None:
    assert len(detect_legs(_cast([(2.0, 0.5, 0.015), (2.5, -0.5, 0.4)]))) == 0


def test_legs_on_the_map_follow_the_pose_and_furniture_legs_on_the_map_are_dropped() -> None:
    scan = _cast([(2.0, 0.0, 0.06)])
    pose = Pose(1.0, 2.0, math.pi / 2)
    legs = detect_legs(scan, pose)
    assert len(legs) == 1 and math.dist(tuple(legs[0]), (1.0, 4.0)) < 0.05
    assert len(detect_legs(scan, pose, static=np.array([[1.0, 4.0]]))) == 0


def test_nearest_legs_are_paired_and_a_lone_leg_stays_alone() -> None:
    groups = pair_legs(np.array([[0.0, 0.0], [0.2, 0.0], [3.0, 0.0]]))
    assert sorted(len(group) for group in groups) == [1, 2]


def test_two_people_walking_past_each_other_keep_their_tracks() -> None:
    tracker = PeopleTracker()
    ids: dict[str, set[int]] = {"a": set(), "b": set()}
    for step in range(60):
        t = step * 0.1
        a, b = (2.0 + 0.6 * t, 1.0), (5.6 - 0.6 * t, 1.6)  # cross at x = 3.8
        legs = np.array([[a[0], a[1] - 0.1], [a[0], a[1] + 0.1],
                         [b[0], b[1] - 0.1], [b[0], b[1] + 0.1]])
        tracks = tracker.update(t, legs)
        if step >= 5:
            assert len(tracks) == 2
            for name, where in (("a", a), ("b", b)):
                nearest = min(tracks, key=lambda track: math.dist(track.position, where))
                assert math.dist(nearest.position, where) < 0.2
                ids[name].add(nearest.id)
    assert len(ids["a"]) == 1 and len(ids["b"]) == 1 and ids["a"] != ids["b"]
    velocity = min(tracker.confirmed(), key=lambda track: track.id).velocity
    assert abs(velocity[0] - 0.6) < 0.15


def test_a_track_dies_when_its_person_is_gone() -> None:
    tracker = PeopleTracker()
    legs = np.array([[2.0, 0.1], [2.0, -0.1]])
    for step in range(5):
        tracker.update(step * 0.1, legs)
    assert len(tracker.confirmed()) == 1
    for step in range(5, 20):
        tracker.update(step * 0.1, np.zeros((0, 2)))
    assert tracker.tracks == []


def test_the_tracker_follows_a_crowd_scene() -> None:
    scene = crowd_scene(3, 2, seconds=6.0)
    tracker = PeopleTracker()
    matched = total = 0
    for frame in scene.frames[10:]:
        tracks = tracker.update(frame.stamp, detect_legs(frame.scan, scene.robot, scene.posts),
                                frame.scan, scene.robot)
        for where in frame.people.values():
            total += 1
            matched += any(math.dist(track.position, where) < 0.5 for track in tracks)
    assert matched / total > 0.8


@pytest.mark.parametrize("posture", POSTURES)
def test_posture_from_the_body_cloud(posture: str) -> None:
    rng = np.random.default_rng(0)
    seen = [posture_from_profile(person_cloud((1.0, 2.0), posture, rng)) for _ in range(20)]
    assert seen.count(posture) >= 18
    assert posture_from_profile(np.zeros((3, 3))) == "unknown"


def test_clothes_colour_survives_light_cast_and_noise() -> None:
    rng = np.random.default_rng(1)
    for name in ("red", "blue", "orange", "black", "white", "green"):
        seen = [clothes_colour(torso_patch(COLOURS[name], rng)) for _ in range(10)]
        assert seen.count(name) >= 8, (name, seen)
