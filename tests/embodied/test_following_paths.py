"""How a follower drives where a doorway or a wall stands between it and the person, and
whom it takes for them once they were lost (``homebot.embodied.following``): fast checks
on the follower's choices alone, no episode run."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from homebot.embodied.following import Following, _Target
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.perception.people import Track
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.world import World


def _follower(world: World, navigator: Navigator, pose: Pose) -> Following:
    sim = Simulation(world, seed=0, navigator=navigator)
    sim.robot_pose = (pose.x, pose.y, pose.theta)
    body = SimBody(sim)
    return Following(body, world, navigator, MotionSearchPlanner(), lambda: pose,
                     lambda legs: np.ones(len(legs), dtype=bool),
                     lambda pose, scan: np.zeros((0, 2)), sim.events)


def _fits(navigator: Navigator, path: list[tuple[float, float]], radius: float) -> bool:
    """Whether a disc of ``radius`` fits along every segment of ``path`` (the start aside)."""
    for (x0, y0), (x1, y1) in itertools.pairwise(path):
        steps = max(1, math.ceil(math.dist((x0, y0), (x1, y1)) / 0.02))
        for t in np.linspace(0.0, 1.0, steps + 1):
            if navigator.clearance_at(x0 + t * (x1 - x0), y0 + t * (y1 - y0)) < radius:
                return False
    return True


def test_a_person_found_again_past_a_door_frame_is_followed_through_the_doorway(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Follow Me seed 257: the robot lost the operator at the entrance door (6, 4) and found
    # them again 2 m on, in the entrance; it stood at the jamb, beside the doorway. The
    # straight line from there ran through the wall.
    here = Pose(5.54, 4.39, 0.6)
    follower = _follower(apartment, apartment_navigator, here)
    target = _Target(1, (5.84, 4.26), (0.0, 0.0), 0.0, trail=[(5.9, 4.6), (5.84, 4.26)])
    follower._take(target, _track((5.57, 2.24)), 1.0)
    path = follower._path_to(here, target.position, target)
    door = apartment.doors["entrance door"].position
    assert min(math.dist(point, door) for point in path) < 0.05  # through its middle
    assert _fits(apartment_navigator, path[1:], 0.25)


def test_a_follower_standing_in_a_doorway_leaves_it_straight(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Follow Me seed 267: the robot stood in the office doorway (9.5, 6), the operator had
    # turned west along the corridor; the slanted way to them ran into the jamb.
    here = Pose(9.4, 5.9, -1.9)
    follower = _follower(apartment, apartment_navigator, here)
    path = follower._through_doorways([here.xy(), (9.0, 5.6), (8.0, 5.6), (7.0, 5.6)])
    assert len(path) == 2
    out = path[-1]
    assert out[0] == pytest.approx(9.5) and out[1] < 5.5  # straight out, into the corridor


def test_a_follower_beside_a_doorway_lines_up_with_it_before_going_through(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Follow Me seed 274's kind: the robot stands 0.58 m from a doorway, off its axis,
    # and the person went through; it lines up first, then crosses square.
    here = Pose(5.5, 4.3, -1.5)
    follower = _follower(apartment, apartment_navigator, here)
    path = follower._through_doorways([here.xy(), (5.7, 4.0), (5.6, 3.2), (5.6, 2.4)])
    door = apartment.doors["entrance door"].position
    assert path[1][0] == pytest.approx(door[0]) and path[1][1] > door[1]  # on its axis
    assert door in path
    assert path[-1][0] == pytest.approx(door[0]) and path[-1][1] < door[1]  # and beyond


def _track(position: tuple[float, float], velocity: tuple[float, float] = (0.0, -0.3),
           number: int = 1) -> Track:
    """A confirmed track at ``position`` (walking south unless told otherwise)."""
    return Track(number, np.array([*position, *velocity]), np.eye(4) * 0.01, born=0.0,
                 seen=1.0, hits=5, confirmed=True)


def test_someone_standing_far_from_where_the_lost_person_walked_needs_their_clothes_seen(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Follow Me seed 276: the operator, walking east along the corridor, was lost behind
    # the bedroom door frame; Maria, standing 3 m on at the end of her crossing, was taken
    # for them.
    here = Pose(2.0, 6.1, -1.4)
    follower = _follower(apartment, apartment_navigator, here)
    target = _Target(1, (2.36, 5.83), (0.4, 0.0), 0.0)
    heading = (2.96, 5.83)
    standing_far = _track((5.71, 4.52), velocity=(0.0, 0.0), number=6)
    assert follower._needs_clothes(target, standing_far, heading)
    # ... but someone walking there, or standing where the person would have stopped, may
    # be them without the camera
    assert not follower._needs_clothes(
        target, _track((5.71, 4.52), velocity=(0.4, 0.0), number=6), heading)
    assert not follower._needs_clothes(
        target, _track((3.4, 5.8), velocity=(0.0, 0.0), number=7), heading)
    # a track once dropped for showing other clothes needs them seen, however long ago
    target.dropped[7] = -100.0
    assert follower._needs_clothes(
        target, _track((3.4, 5.8), velocity=(0.4, 0.0), number=7), heading)


def test_a_follower_heading_into_a_wall_beside_its_way_turns_rather_than_crawl(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Follow Me seed 262's kind: the robot came out of a doorway heading across the
    # corridor, the person walked on along it; the straight strip ahead met the far wall,
    # and the local controller crawled at 0.1 m/s. The way along the corridor is free.
    here = Pose(8.0, 5.5, 2.3)
    follower = _follower(apartment, apartment_navigator, here)
    follower.body.tick()
    twist = follower._pursue(here, [here.xy(), (7.5, 5.5), (6.5, 5.5)])
    assert twist is not None
    assert twist.vx == 0.0 and twist.wz > 0.3  # turns left, towards the corridor's way
