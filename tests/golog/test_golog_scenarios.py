"""``homebot scenario rips|order_cups|maze|cup_moved`` and ``homebot bench golog``, in-process."""

from __future__ import annotations

import argparse
import json
from typing import Any

import pytest

from homebot.app import RunSettings
from homebot.bench import golog as golog_bench
from homebot.cli import main
from homebot.cli.scenario import run_builder
from homebot.scenarios.library import cup_moved, maze, order_cups, rips
from homebot.scenarios.running import ScenarioRun
from homebot.world import World

SUMMARY_KEYS = {"scenario", "success", "actions", "speech"}


def test_rips_registers_through_the_skills_in_the_simulated_home() -> None:
    summary = rips.run(argparse.Namespace(seed=0, disturb=0.0), None, run_builder())
    assert summary["success"] and summary["handed_over"]
    skills = [step["skill"] for step in summary["actions"]]
    assert skills[0] == "pick" and "give" in skills and skills[-1] == "navigate"
    assert all(step["status"] == "verified" for step in summary["actions"])
    assert summary["golog_actions"][:2] == ["grasp(Registration Sheet)", "park_arm"]
    assert "If you want, you can now test my emergency stop button." in summary["speech"]
    assert summary["speech"][0] == "I am ready. Please press my start button."


def test_rips_writes_golog_steps_into_the_event_log() -> None:
    logs: list[object] = []
    build = run_builder()

    def keep(world: World, **options: Any) -> ScenarioRun:
        made = build(world, **options)
        logs.append(made.events)
        return made

    rips.run(argparse.Namespace(seed=0, disturb=0.0), None, keep)
    kinds = [event.kind for event in logs[0].events]  # type: ignore[attr-defined]
    assert "golog.exogenous" in kinds and "golog.action" in kinds and "skill.start" in kinds
    assert kinds.index("golog.exogenous") < kinds.index("golog.action", kinds.index(
        "golog.exogenous"))


def test_rips_is_the_same_run_for_the_same_seed() -> None:
    first = rips.run(argparse.Namespace(seed=4, disturb=1.0), None, run_builder())
    second = rips.run(argparse.Namespace(seed=4, disturb=1.0), None, run_builder())
    assert first == second


@pytest.mark.parametrize("seed", range(4))
def test_order_cups_uses_the_fewest_moves(seed: int) -> None:
    summary = order_cups.run(argparse.Namespace(seed=seed, goal="blue,green,red", horizon=4),
                             None, run_builder())
    assert summary["success"]
    assert summary["moves"] == summary["fewest_moves"]
    assert summary["speech"] == ["That is it. I am done."]


def test_cup_moved_is_detected_by_a_marker_and_replanned() -> None:
    summary = cup_moved.run(argparse.Namespace(seed=0, after=1), None, run_builder())
    assert summary["success"] and summary["replans"] == 1
    assert summary["markers"][0].startswith("poss(move_cup(")
    assert summary["moves_after_disturbance"] == summary["fewest_after_disturbance"]


def test_cup_moved_unseen_is_found_when_the_next_move_fails() -> None:
    summary = cup_moved.run(argparse.Namespace(seed=0, after=1, unseen=True), None, run_builder())
    assert summary["success"] and summary["markers"] == ["done(move_cup(red, p2, p1))"]


def test_order_cups_through_the_skills_in_the_home() -> None:
    summary = order_cups.run(argparse.Namespace(seed=1, goal="red,green,blue", horizon=4,
                                                home=True), None, run_builder())
    assert summary["success"] and summary["moves"] == summary["fewest_moves"] == 4
    skills = [step["skill"] for step in summary["skills"]]
    assert skills[:4] == ["look"] * 4 and skills[4:6] == ["pick", "place"]
    assert all(step["status"] == "verified" for step in summary["skills"])


@pytest.mark.parametrize(("unseen", "marker"), [
    (False, "poss(move_cup(red, p2, p1))"), (True, "done(move_cup(red, p2, p1))")])
def test_cup_moved_in_the_home_is_noticed_and_replanned(unseen: bool, marker: str) -> None:
    summary = cup_moved.run(argparse.Namespace(seed=0, after=1, unseen=unseen, home=True),
                            None, run_builder())
    assert summary["success"] and summary["markers"] == [marker]
    assert summary["moves_after_disturbance"] == summary["fewest_after_disturbance"]


def test_maze_reaches_the_goal() -> None:
    summary = maze.run(argparse.Namespace(seed=0, horizon=8), None, run_builder())
    assert summary["success"] and summary["end"] == [5, 1]
    assert 0 < summary["success_probability"] < 1


def test_in_the_maze_the_robot_can_slip_down_the_stairs() -> None:
    summary = maze.run(argparse.Namespace(seed=10, horizon=8), None, run_builder())
    assert not summary["success"] and summary["fell"] and summary["end"] == [3, 1]


def test_scenario_json_through_the_command_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "cup_moved", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert set(summary) >= SUMMARY_KEYS and summary["scenario"] == "cup_moved"


def test_a_bad_goal_order_exits_2_with_a_hint(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "order_cups", "--goal", "red,red,blue"]) == 2
    assert "--goal blue,red,green" in capsys.readouterr().err.replace("\n", " ")


@pytest.mark.parametrize(("argv", "words"), [
    (["scenario", "maze", "--horizon", "0"], "give 1 or more"),
    (["scenario", "cup_moved", "--after", "-1"], "0 or more"),
])
def test_scenario_numbers_out_of_range_exit_2(argv: list[str], words: str,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    assert words in capsys.readouterr().err.replace("\n", " ")


def test_the_benchmark_reports_nodes_and_time() -> None:
    report = golog_bench.run(argparse.Namespace(repeats=1, cups_horizon=3, maze_horizon=4),
                             None)
    for figures in report["figures"].values():
        assert figures["nodes"] > 0 and figures["nodes_per_second"] > 0


def test_with_monitoring_off_a_finished_skill_is_a_done_action() -> None:
    from homebot.app import build_run
    from homebot.golog import State
    from homebot.golog.skill_executor import SkillExecutor
    from homebot.task import Step
    from homebot.world import World

    run = build_run(RunSettings(world=World.load("apartment"), monitoring=False))
    executor = SkillExecutor(run.executive, {"say": lambda action: [Step("say",
                                                                       {"text": action[1]})]})
    assert executor.execute(("say", "hello"), State())
    assert executor.steps[0]["status"] == "finished"
