"""A person asked to "follow me" walks after the robot by their own rule (``homebot.sim.guided``):
at their pace, along its trail, about a metre behind, stopping when it stops; one who
wanders off stays apart until the robot asks again from near."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from homebot.navigation import Navigator
from homebot.robot import Twist
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.guided import HEARS_AGAIN, PERSONAL_SPACE, Personality, personality_of
from homebot.world import World

pytest.importorskip("numba")  # the SimBody's laser


def _say(body: SimBody, text: str) -> None:
    body.speaker().play(np.zeros(1600, dtype=np.int16), text=text)


def _drive(body: SimBody, twist: Twist, seconds: float
           ) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Drive the base with ``twist`` for ``seconds``; Alex's and the robot's positions after
    every tick."""
    person, robot = [], []
    for _ in range(round(seconds / body.tick_period)):
        body.command_velocity(twist)
        body.tick()
        person.append(body.sim.people["Alex"].position)
        robot.append(body.sim.robot_pose[:2])
    return person, robot


def _drive_along(body: SimBody, points: list[tuple[float, float]], speed: float = 0.4
                 ) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """Drive the base through ``points`` (turning on the spot, then straight); Alex's and
    the robot's positions after every tick."""
    person, robot = [], []
    for point in points:
        while math.dist(body.sim.robot_pose[:2], point) > 0.05:
            x, y, theta = body.sim.robot_pose
            error = math.remainder(math.atan2(point[1] - y, point[0] - x) - theta, math.tau)
            body.command_velocity(Twist(speed if abs(error) < 0.1 else 0.0, 0.0,
                                        max(-1.0, min(1.0, 2.0 * error))))
            body.tick()
            person.append(body.sim.people["Alex"].position)
            robot.append(body.sim.robot_pose[:2])
    return person, robot


def _guided(apartment: World, navigator: Navigator, personality: Personality,
            robot: tuple[float, float], person: tuple[float, float]) -> SimBody:
    sim = Simulation(apartment, seed=3, navigator=navigator)
    sim.robot_pose = (*robot, 0.0)
    body = SimBody(sim)
    sim.move_person("Alex", person)
    body.hearing.personalities["Alex"] = personality
    _say(body, "Alex, please follow me.")
    return body


def test_a_guided_person_walks_after_the_robot_and_stops_when_it_stops(
        apartment: World, apartment_navigator: Navigator) -> None:
    # the robot in the living room, Alex beside the couch: out through the door, along
    # the corridor
    body = _guided(apartment, apartment_navigator, Personality.STEADY, (3.0, 3.0), (3.6, 2.0))
    sim = body.sim
    walk = body.hearing.guided
    assert walk is not None and body.hearing.coming_along == "Alex"
    person, robot = _drive_along(body, [(2.5, 3.2), (2.5, 5.0), (7.0, 5.0)])
    assert sim.robot_room() == "corridor"
    steps = [math.dist(a, b) for a, b in itertools.pairwise(person)]
    assert max(steps) <= walk.pace * body.tick_period + 1e-9  # walked, never jumped
    assert sim.people["Alex"].room == "corridor"  # came through the door after it
    keep = apartment.robot.radius + PERSONAL_SPACE
    assert min(math.dist(p, r) for p, r in zip(person, robot, strict=True)) >= keep - 1e-9
    assert not sim.collisions
    # the robot stops: Alex comes up to about a metre behind and stands
    resting, _ = _drive(body, Twist(), 10.0)
    assert resting[-1] == resting[-40]
    assert math.dist(resting[-1], sim.robot_pose[:2]) <= walk.gap + 0.05
    assert resting[-1][0] < sim.robot_pose[0]  # behind it, where it came from


def test_a_lagging_person_is_slower_than_the_robot_and_stops_to_look_round(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _guided(apartment, apartment_navigator, Personality.LAGGING, (1.5, 5.0), (0.6, 5.0))
    walk = body.hearing.guided
    assert walk is not None and walk.pace < 0.5
    person, robot = _drive(body, Twist(0.45, 0.0, 0.0), 20.0)
    steps = [math.dist(a, b) for a, b in itertools.pairwise(person)]
    assert max(steps) <= walk.pace * body.tick_period + 1e-9
    assert math.dist(person[-1], robot[-1]) > 3.0  # fell behind
    standing = sum(step == 0.0 for step in steps)
    assert standing > 1.0 / body.tick_period  # looked round for a while on the way


def test_a_person_who_wandered_off_follows_again_only_when_asked_from_near(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _guided(apartment, apartment_navigator, Personality.WANDERING, (1.0, 5.0),
                   (0.4, 5.0))
    sim = body.sim
    walk = body.hearing.guided
    assert walk is not None
    _drive(body, Twist(0.4, 0.0, 0.0), 20.0)
    _drive(body, Twist(), 5.0)
    assert walk.wandered
    off = [e for e in sim.events.of_kind("sim.person") if e.data["did"] == "wandered off"]
    assert len(off) == 1
    spot = sim.people["Alex"].position
    assert math.dist(spot, sim.robot_pose[:2]) > HEARS_AGAIN
    _say(body, "Alex, please follow me.")  # from afar: they stay
    _drive(body, Twist(), 3.0)
    assert walk.wandered and sim.people["Alex"].position == spot
    # the robot comes back near them and asks again: they follow
    sim.robot_pose = (spot[0] + 1.2, spot[1], math.pi) if sim.world.room_at(
        spot[0] + 1.2, spot[1]) == sim.people["Alex"].room else (spot[0] - 1.2, spot[1], 0.0)
    _say(body, "Alex, please follow me.")
    assert not walk.wandered
    assert list(sim.events.of_kind("sim.person"))[-1].data["did"] == "follows again"


def test_asked_something_else_the_guided_person_stops_following(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = _guided(apartment, apartment_navigator, Personality.STEADY, (1.5, 5.0), (0.6, 5.0))
    walk = body.hearing.guided
    _say(body, "Alex, I am waiting for you.")  # a remark: they go on following
    assert body.hearing.coming_along == "Alex"
    _say(body, "Alex, what would you like to drink?")
    assert walk is not None and walk.finished and body.hearing.coming_along is None
    before = body.sim.people["Alex"].position
    _drive(body, Twist(0.4, 0.0, 0.0), 5.0)
    assert body.sim.people["Alex"].position == before


def test_personalities_are_drawn_by_seed_in_their_shares() -> None:
    drawn = [personality_of(seed, "Alex") for seed in range(400)]
    assert drawn == [personality_of(seed, "Alex") for seed in range(400)]
    for personality, share in ((Personality.STEADY, 0.6), (Personality.LAGGING, 0.2),
                               (Personality.WANDERING, 0.2)):
        assert abs(drawn.count(personality) / len(drawn) - share) < 0.07


def test_a_guided_person_does_not_stop_in_a_doorway_or_out_of_sight(
        apartment: World, apartment_navigator: Navigator) -> None:
    # the robot stops 1.3 m past the living room door: a metre of trail behind it is the
    # doorway, where nobody stands about (and the robot's laser tells no legs from jambs)
    body = _guided(apartment, apartment_navigator, Personality.STEADY, (3.0, 2.9), (3.6, 2.0))
    sim = body.sim
    _drive_along(body, [(2.5, 3.0), (2.5, 5.3)], speed=0.3)
    resting, _ = _drive(body, Twist(), 8.0)
    door = apartment.doors["living room door"].position
    assert resting[-1] == resting[-20]  # they stand
    assert math.dist(resting[-1], door) >= 0.6
    assert sim.people["Alex"].room == "corridor"
    assert math.dist(resting[-1], sim.robot_pose[:2]) >= apartment.robot.radius + PERSONAL_SPACE
