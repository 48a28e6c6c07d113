"""The embodied robot guides someone by tracking them (``homebot.embodied.guiding``): the
person walks after it by their own rule (``homebot.sim.guided``), and the referee judges by
the simulator's truth (``homebot.trials.guiding``)."""

from __future__ import annotations

from typing import Any

import pytest

from homebot.app.guiding import run_guide
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.guided import PACE_LIMIT, Personality
from homebot.trials.guiding import GOAL_REACH, arranged_arena
from homebot.world import World

pytest.importorskip("numba")  # the SimBody's laser
pytest.importorskip("cv2")  # the robot's perception
pytest.importorskip("pocketsphinx")  # the robot hears the person's "yes"


def _guide(apartment: World, navigator: Navigator, personality: Personality
           ) -> tuple[Simulation, dict[str, Any]]:
    """Alex, in the living room, guided to the office desk: through the living room door,
    along the corridor and through the office door."""
    sim = Simulation(apartment, seed=5, navigator=navigator)
    arena = arranged_arena(sim, "Alex", (3.6, 2.9), (3.6, 1.7), "desk", personality)
    return sim, run_guide(arena, navigator).to_dict()


def test_the_robot_guides_someone_to_the_goal_and_they_walk_there(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim, episode = _guide(apartment, apartment_navigator, Personality.STEADY)
    assert episode["end_distance"] is not None and episode["end_distance"] <= GOAL_REACH
    assert episode["success"] and episode["at_goal"] and episode["person_collisions"] == 0
    assert episode["robot_verdict"] == "verified"  # the robot saw them there itself
    assert 0.0 < episode["fastest"] <= PACE_LIMIT + 1e-9  # they walked, never jumped
    assert sim.people["Alex"].room == "office"


def test_someone_who_wanders_off_is_noticed_fetched_and_brought_to_the_goal(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim, episode = _guide(apartment, apartment_navigator, Personality.WANDERING)
    assert episode["wandered_off"] == 1  # the truth: they walked off
    lost = list(sim.events.of_kind("robot.guide_lost"))
    fetched = list(sim.events.of_kind("robot.guide_fetched"))
    assert lost and fetched  # the robot noticed, went back and asked again
    assert lost[0].time < fetched[0].time
    assert episode["fetched"] >= 1  # they heard it from near, and followed again
    assert episode["end_distance"] is not None and episode["end_distance"] <= GOAL_REACH
    assert episode["person_collisions"] == 0
    assert episode["fastest"] <= PACE_LIMIT + 1e-9
