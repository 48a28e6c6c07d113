"""People who walk a route of their own (``homebot.sim.routes``): at their pace, through doors
they open, round a robot in their way, and saying what they say on arriving."""

from __future__ import annotations

import itertools
import math

import pytest

from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.routes import RouteWalk, plan_route
from homebot.world import DoorState, World

pytest.importorskip("numba")  # the SimBody's laser


def _walk(body: SimBody, name: str, seconds: float) -> list[tuple[float, float]]:
    """Tick ``seconds``; the person's position after every tick."""
    positions = []
    for _ in range(round(seconds / body.tick_period)):
        body.tick()
        positions.append(body.sim.people[name].position)
    return positions


def test_a_person_walks_their_route_at_their_pace_and_opens_a_shut_door(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim = Simulation(apartment, seed=3, navigator=apartment_navigator)
    sim.robot_pose = (11.0, 9.0, 0.0)  # in the office, out of the way
    body = SimBody(sim)
    sim.door_state["living room door"] = DoorState.CLOSED
    sim.move_person("Alex", (2.5, 2.5))
    route = plan_route(sim, (2.5, 2.5), [(2.5, 5.0), (9.0, 5.0)])
    assert route is not None
    arrived: list[float] = []
    body.people.walk_route(RouteWalk("Alex", route, 0.5, pause_chance=0.0,
                                     at_end=lambda: arrived.append(sim.clock.now())))
    positions = _walk(body, "Alex", 30.0)
    steps = [math.dist(a, b) for a, b in itertools.pairwise(positions)]
    assert max(steps) <= 0.5 * body.tick_period + 1e-9  # walked, never jumped
    assert sim.door_state["living room door"] is DoorState.OPEN  # opened on the way
    assert any(e.data.get("did") == "opened" for e in sim.events.of_kind("sim.person"))
    assert arrived and math.dist(sim.people["Alex"].position, (9.0, 5.0)) < 1e-6
    assert sim.people["Alex"].room == "corridor"


def test_a_walker_waits_for_a_robot_in_the_way_then_goes_round_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim = Simulation(apartment, seed=3, navigator=apartment_navigator)
    sim.robot_pose = (6.0, 5.0, 0.0)  # in the corridor, on the walker's way
    body = SimBody(sim)
    sim.move_person("Alex", (3.0, 5.0))
    body.people.walk_route(RouteWalk("Alex", [(9.0, 5.0)], 0.6, pause_chance=0.0))
    positions = _walk(body, "Alex", 40.0)
    nearest = min(math.dist(p, (6.0, 5.0)) for p in positions)
    assert nearest >= 0.6  # never into the robot
    assert math.dist(positions[-1], (9.0, 5.0)) < 1e-6  # but on past it


def test_asked_to_go_ahead_a_person_walks_there_and_says_they_are_there(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim = Simulation(apartment, seed=3, navigator=apartment_navigator)
    sim.robot_pose = (3.0, 1.0, 0.0)
    body = SimBody(sim)
    sim.move_person("Alex", (3.6, 2.0))
    body.speaker().play(_silence(), text="Alex, please go ahead to the kitchen, I will "
                                         "follow you.")
    positions = _walk(body, "Alex", 60.0)
    steps = [math.dist(a, b) for a, b in itertools.pairwise(positions)]
    assert max(steps) < 0.05  # a walk, not a jump
    assert sim.people["Alex"].room == "kitchen"
    said = [e.data["text"] for e in sim.events.of_kind("sim.person_said")]
    assert said[-1] == "We are here."


def _silence() -> object:
    import numpy as np

    return np.zeros(1600, dtype=np.int16)
