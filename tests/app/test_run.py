"""``homebot.app``: one run, built from typed settings, the same for every interface."""

from __future__ import annotations

import pytest

from homebot.app import (
    Fidelity,
    RunSettings,
    build_run,
    conversation_for,
    disturbed,
)
from homebot.navigation import Navigator
from homebot.sim import InteractiveResponder, SimRobot
from homebot.task import Step, Task
from homebot.world import World


def test_a_symbolic_run_has_the_simulated_robot_and_no_body(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, seed=3,
                                retries={"pick": 2}, time_limit=60.0))
    assert isinstance(run.robot, SimRobot)
    assert run.body is None and run.localisation is None
    assert run.simulation.seed == 3
    assert run.context.retries == {"pick": 2}
    assert run.executive.time_limit == 60.0
    assert run.events is run.simulation.events


def test_settings_are_plain_values_with_the_symbolic_fidelity_by_default(
        apartment: World) -> None:
    settings = RunSettings(world=apartment)
    assert settings.fidelity is Fidelity.SYMBOLIC
    assert settings.disturbances is None and settings.retries == {}
    with pytest.raises(TypeError):
        RunSettings(apartment)  # type: ignore[call-arg]


def test_an_interactive_run_asks_the_person_at_the_keyboard(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator,
                                interactive=True))
    assert isinstance(run.simulation.responder, InteractiveResponder)


def test_the_same_settings_make_the_same_run(apartment: World,
                                             apartment_navigator: Navigator) -> None:
    settings = RunSettings(world=apartment, navigator=apartment_navigator, seed=5,
                           disturbances=disturbed(1.0))
    task = Task((Step("navigate", {"to": "kitchen"}),))
    first, second = build_run(settings), build_run(settings)
    assert first.run(task).to_dict() == second.run(task).to_dict()
    assert [event.kind for event in first.events.events] == \
        [event.kind for event in second.events.events]


def test_the_conversation_reads_commands_by_the_robots_beliefs(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator))
    conversation = conversation_for(run, question_cost=0.5)
    assert conversation.readings is not None
    readings = conversation.readings()
    assert readings.question == 0.5
    assert readings.object_at == {name: where for name, where in
                                  run.context.beliefs.object_at.items() if where}
    assert conversation.run == run.run
