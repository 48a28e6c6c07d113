"""The receive skill: the robot takes what a person hands it, and checks its hand."""

from __future__ import annotations

import pytest

from homebot.app import Run, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.sim import PERSON_PREFIX
from homebot.skills import ErrorCode, Status, skill_named
from homebot.world import World


@pytest.fixture
def run(apartment: World, apartment_navigator: Navigator) -> Run:
    return build_run(RunSettings(world=apartment, navigator=apartment_navigator))


def test_the_robot_takes_what_the_operator_hands_it(run: Run) -> None:
    operator = run.world.model.operator
    thing = sorted(run.world.objects)[0]
    run.simulation.object_location[thing] = PERSON_PREFIX + operator
    outcome = skill_named("receive").run(run.context, {"person": "operator"})
    assert outcome.status is Status.VERIFIED, outcome.message
    assert outcome.data["object"] == thing
    hand = outcome.data["hand"]
    assert run.simulation.hands[hand] == thing  # the truth: it is in the robot's hand
    assert run.context.beliefs.holding[hand] == thing


def test_nothing_given_is_aborted_and_full_hands_fail(run: Run) -> None:
    outcome = skill_named("receive").run(run.context, {"person": "operator"})
    assert outcome.status is Status.ABORTED and outcome.error is ErrorCode.NOT_GRASPED
    for hand in run.simulation.hands:
        run.context.beliefs.took(f"thing-{hand}", hand)
    full = skill_named("receive").run(run.context, {"person": "operator"})
    assert full.status is Status.FAILED and full.error is ErrorCode.HANDS_FULL
