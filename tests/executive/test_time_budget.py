"""The task's time budget (--time-limit): searches stop at it and say where they looked."""

from __future__ import annotations

import argparse

import pytest

from homebot.app import Run, RunSettings, build_run
from homebot.cli import command_line_argument_parser
from homebot.cli.options import GPSR_TIME_LIMIT, time_limit
from homebot.language import Vocabulary, parse_command
from homebot.navigation import Navigator
from homebot.task import Step, Task
from homebot.world import World


def _run_out_red_wine(apartment: World, navigator: Navigator,
                      limit: float | None) -> tuple[Run, Task]:
    run = build_run(RunSettings(world=apartment, navigator=navigator, time_limit=limit))
    run.simulation.object_location["red wine"] = None  # drunk: the world file says otherwise
    return run, parse_command("bring me the red wine", Vocabulary.from_world(apartment)).to_task()


@pytest.mark.parametrize("limit", [GPSR_TIME_LIMIT, 120.0])
def test_a_run_out_object_ends_within_the_time_limit_naming_the_places_searched(
        apartment: World, apartment_navigator: Navigator, limit: float) -> None:
    run, task = _run_out_red_wine(apartment, apartment_navigator, limit)
    report = run.run(task)
    assert not report.success
    assert report.sim_time <= limit  # including the way back to the operator
    assert report.steps[-1].error == "out_of_time"
    assert "anywhere I looked: the kitchen counter, the " in report.reason
    looked = report.reason.split("anywhere I looked: ")[1]
    assert looked.count("the ") >= 2
    assert any("ran out of time" in text for text in report.speech)
    # The robot went back to the operator to say so.
    assert run.simulation.distance_to(run.simulation.people["Alex"].position) < 1.5


def test_without_a_budget_the_search_covers_the_home_and_names_every_place(
        apartment: World, apartment_navigator: Navigator) -> None:
    run, task = _run_out_red_wine(apartment, apartment_navigator, None)
    report = run.run(task)
    assert not report.success and report.sim_time > GPSR_TIME_LIMIT
    assert report.steps[-1].error == "not_found"
    assert all(f"the {place}" in report.reason for place in apartment.placements)


def test_a_step_is_not_started_once_the_budget_is_spent(apartment: World,
                                                        apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, time_limit=10.0))
    report = run.run(Task((Step("navigate", {"to": "bed"}), Step("navigate", {"to": "desk"}))))
    assert [step.status for step in report.steps] == ["verified", "failed"]
    assert report.steps[1].error == "out_of_time"


def test_gpsr_commands_default_to_five_simulated_minutes() -> None:
    parser = command_line_argument_parser()
    assert parser.parse_args(["do", "bring me the cola"]).time_limit == 300.0
    assert parser.parse_args(["run-task", "task.yaml"]).time_limit is None
    assert parser.parse_args(["run-task", "t.yaml", "--time-limit", "5m"]).time_limit == 300.0


@pytest.mark.parametrize(("text", "seconds"), [("300", 300.0), ("90s", 90.0), ("2m", 120.0),
                                               ("1.5 min", 90.0), ("none", None)])
def test_time_limits_parse(text: str, seconds: float | None) -> None:
    assert time_limit(text) == seconds


@pytest.mark.parametrize("text", ["0", "-3", "nan", "inf", "5 parsecs", "", "2d"])
def test_bad_time_limits_are_refused(text: str) -> None:
    with pytest.raises(argparse.ArgumentTypeError, match="not a time limit"):
        time_limit(text)


def test_a_person_search_stops_at_the_budget_naming_the_rooms(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, time_limit=90.0))
    report = run.run(Task((Step("find_person", {"person": {"gesture": "pointing_left"}}),)))
    assert not report.success and report.sim_time <= 90.0
    assert report.steps[0].error == "out_of_time"
    assert "I ran out of time looking for a person pointing to the left; I looked in the" in (
        report.reason)


def test_engines_that_run_steps_themselves_get_the_budget(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(world=apartment, navigator=apartment_navigator, time_limit=60.0))
    run.simulation.object_location["red wine"] = None
    outcome = run.executive.run_step("find_object", {"object": "red wine"})
    assert outcome.error is not None and outcome.error.value == "out_of_time"
    assert run.robot.now() <= 60.0
