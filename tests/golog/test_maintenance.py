"""Self-maintenance: requirements from the constraints, δ → δ′, repairs, judged by the sim's log."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from homebot.cli import main
from homebot.errors import GologError
from homebot.golog import Interpreter
from homebot.golog.build import do
from homebot.golog.domains import rips_theory
from homebot.golog.maintenance import (
    MaintenanceInterpreter,
    ProjectionExecutor,
    add_management,
    load_maintenance,
    maintenance_from_text,
)
from homebot.scenarios.maintained import (
    ComponentExecutor,
    judge,
    run_maintained,
    shipped_maintenance,
    simulated_components,
)

SMALL = """
maintenance:
  components:
    - {name: laser, initial: off}
    - {name: collision_avoidance, initial: off}
    - {name: arm, kind: posture, states: [parked, unparked], initial: unparked}
  constraints:
%s
"""


def _small(*constraints: str) -> str:
    return SMALL % "\n".join(f"    - {c}" for c in constraints)


def test_requirements_follow_from_constraints_together_by_path_consistency() -> None:
    maintenance = maintenance_from_text(_small(
        "goto_place within collision_avoidance=running",
        "collision_avoidance=running during laser=running",
        "goto_place disjoint arm=unparked"))
    needs = maintenance.requirements("goto_place")
    # the laser is named by no constraint on goto_place: it follows through collision avoidance
    assert needs.must == {"collision_avoidance": "running", "laser": "running"}
    assert needs.must_not == {"arm": frozenset({"unparked"})}
    assert sorted(str(m) for m in needs.markers) == [
        "arm≠unparked while goto_place", "collision_avoidance=running while goto_place",
        "laser=running while goto_place"]
    # the laser must start first: collision avoidance runs during it
    states = {"laser": "off", "collision_avoidance": "off", "arm": "unparked"}
    assert maintenance.plan(states, needs) == [
        ("set_posture", "arm", "parked"), ("start", "laser"), ("start", "collision_avoidance")]
    # a crashed module is restarted, one that runs is left alone
    states = {"laser": "running", "collision_avoidance": "failed", "arm": "parked"}
    assert maintenance.plan(states, needs) == [("restart", "collision_avoidance")]
    assert maintenance.requirements("say").empty


def test_a_state_that_must_begin_after_an_action_is_a_commitment_on_the_todo_list() -> None:
    maintenance = maintenance_from_text(_small("give within arm=unparked",
                                               "give before arm=parked"))
    needs = maintenance.requirements("give")
    assert needs.must == {"arm": "unparked"}
    assert [str(c) for c in needs.after] == ["arm=parked after give"]


@pytest.mark.parametrize(("constraints", "named"), [
    (("goto_place before say", "say before goto_place"),
     ["goto_place before say", "say before goto_place"]),
    (("goto_place within laser=running", "goto_place disjoint laser=running"),
     ["goto_place within laser=running", "goto_place disjoint laser=running"]),
    # only together with 'a component is in one state' (running and off are disjoint)
    (("goto_place within laser=running", "goto_place within laser=off", "say after goto_place"),
     ["goto_place within laser=running", "goto_place within laser=off"]),
])
def test_an_inconsistent_set_names_the_constraints_that_conflict(
        constraints: tuple[str, ...], named: list[str]) -> None:
    with pytest.raises(GologError) as raised:
        maintenance_from_text(_small(*constraints), "robot.yaml")
    message = str(raised.value)
    assert "cannot all hold" in message
    for text in named:
        assert text in message
    for text in set(constraints) - set(named):
        assert text not in message


@pytest.mark.parametrize(("text", "expected"), [
    (_small("goto_place whilst laser=running"), "'whilst' is not an Allen relation"),
    (_small("goto_place within lazer=running"), "no component 'lazer'"),
    (_small("goto_place within laser=on"), "'on' is not a state of laser"),
    (_small("goto_place within"), "a constraint is 'SUBJECT RELATION OBJECT'"),
    (SMALL.replace("initial: off}", "initial: off, colour: red}", 1) % "",
     "robot.yaml: line 4: maintenance.components.0.colour: unknown field"),
    ("maintenance:\n  components: []\n", "robot.yaml: line 2: maintenance.components"),
    ("name: home\n", "no 'maintenance' section"),
    (SMALL.replace("kind: posture, states: [parked, unparked], ", "kind: posture, ")
     % "    - say within laser=running",
     "a posture needs 'states'"),
])
def test_a_bad_section_is_reported_with_file_and_line(text: str, expected: str) -> None:
    with pytest.raises(GologError, match=re.escape(expected)):
        maintenance_from_text(text, "robot.yaml")


def test_an_unknown_action_is_named_against_the_theory() -> None:
    maintenance = maintenance_from_text(_small("goto within laser=running"), "robot.yaml")
    with pytest.raises(GologError, match="'goto' is not an action of the theory 'rips'"):
        maintenance.check(rips_theory())


def test_a_world_file_may_carry_the_maintenance_section(tmp_path: Path) -> None:
    from homebot.world import World

    source = Path(__file__).resolve().parents[2] / "src" / "homebot" / "data" / "worlds"
    text = (source / "apartment.yaml").read_text(encoding="utf-8")
    path = tmp_path / "home.yaml"
    path.write_text(text + _small("goto_place within laser=running"), encoding="utf-8")
    assert World.load(path).name
    assert load_maintenance(path).requirements("goto_place").must == {"laser": "running"}


def _projected() -> MaintenanceInterpreter:
    maintenance = shipped_maintenance("rips")
    theory = add_management(rips_theory(), maintenance)
    pressed = [("press_start_button",)]
    executor = ProjectionExecutor(theory, events=lambda clock, truth: pressed if clock >= 2
                                  and truth.get(("start_button",)) != "on" else [])
    return MaintenanceInterpreter(theory, executor, maintenance)


def test_the_transformed_rips_program_starts_what_driving_needs_first() -> None:
    interpreter = _projected()
    run = interpreter.run(do("rips"))
    assert run.success
    actions = run.detail.actions
    first_goto = actions.index("goto_place(Registration Desk)")
    assert actions[:first_goto].index("start(laser)") < actions.index(
        "start(collision_avoidance)") < first_goto
    assert actions[first_goto - 4:first_goto][0] == "set_posture(arm, parked)"
    # after the hand-over the arm is parked: the todo list's commitment
    give = actions.index("give(Registration Sheet, TC)")
    assert actions[give - 1] == "set_posture(arm, unparked)"
    assert actions[give + 1] == "set_posture(arm, parked)"
    step = next(s for s in interpreter.transformations if s.action.startswith("goto_place"))
    assert step.program.startswith("set_posture(arm, parked); start(laser); ")
    assert "laser=running while goto_place" in step.todo


def test_crashes_are_repaired_before_the_dependent_action_and_no_constraint_is_broken() -> None:
    crashes = interrupted = 0
    for seed in range(6):
        result = run_maintained(seed=seed, mean_time_to_failure=120.0, restart_failure=0.0,
                                start_failure=0.0)
        assert result.success, result.reason
        assert result.detail.verdict.violations == []
        assert result.detail.verdict.unrepaired == []
        crashes += result.detail.verdict.crashes
        interrupted += sum(e["kind"] == "maintenance.interrupted" for e in result.detail.log)
    assert crashes > 6 and interrupted > 0  # there were crashes, some in the middle of actions


def test_the_same_seed_gives_the_same_run() -> None:
    assert run_maintained(seed=4).detail.events == run_maintained(seed=4).detail.events


def test_a_module_that_does_not_restart_is_named_to_the_operator() -> None:
    result = run_maintained(seed=1, mean_time_to_failure=40.0, restart_failure=1.0,
                            start_failure=0.0)
    assert not result.success
    told = result.detail.operator
    assert told and "does not come back after 3 restart(s)" in told[0]
    component = result.detail.operator[0].split()[1]
    assert component in shipped_maintenance("rips").components
    assert result.reason == result.detail.operator[0]


def test_the_judge_sees_violations_when_nothing_maintains_the_components() -> None:
    maintenance = shipped_maintenance("rips")
    theory = add_management(rips_theory(), maintenance)
    simulation = simulated_components(maintenance, seed=0, mean_time_to_failure=1e9,
                                      start_failure=0.0, restart_failure=0.0)
    Interpreter(theory, ComponentExecutor(theory, simulation)).run(do("rips"))
    verdict = judge(simulation.events, maintenance)
    assert verdict.actions == 11
    assert any("goto_place within collision_avoidance=running" in v for v in verdict.violations)


def test_cli_show_prints_the_transformed_program_and_the_todo_list(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "maintain", "rips", "--show"]) == 0
    out = capsys.readouterr().out
    assert "before goto_place(Registration Desk):" in out
    assert "δ′ = set_posture(arm, parked); start(laser); start(collision_avoidance); " in out
    assert "todo: arm=parked after give" in out


def test_cli_reports_conflicting_constraints_with_exit_2(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "robot.yaml"
    bad.write_text(_small("goto_place before say", "say before goto_place"), encoding="utf-8")
    assert main(["golog", "maintain", "rips", "--maintenance", str(bad), "--show"]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "these conflict: goto_place before say" in err and "say before goto_place" in err


def test_cli_runs_with_crashes(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "maintain", "rips", "--seed", "2"]) == 0
    assert "0 action(s) with a violated constraint" in capsys.readouterr().out


def test_bench_reports_repairs_and_speed(capsys: pytest.CaptureFixture[str]) -> None:
    import json

    assert main(["bench", "maintenance", "--runs", "2", "--actions", "3", "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    repairs = figures["repairs"]
    assert repairs["runs"] == 2 and repairs["actions_with_violated_constraint"] == 0
    assert repairs["crashes"] == repairs["repaired_before_dependent_action"] + repairs[
        "crashes_not_needed_again"] + repairs["crashes_unrepaired"]
    assert figures["speed"]["components"] == 10 and figures["speed"]["constraints"] == 30


def test_the_generated_section_is_consistent_and_of_the_size_asked() -> None:
    import random

    from homebot.bench.maintenance import synthetic_maintenance

    generated = synthetic_maintenance(random.Random(5), 10, 30)
    assert len(generated.components) == 10 and len(generated.constraints) == 30
    generated.check()


def test_a_state_that_must_have_ended_before_the_action_is_gone_through_or_ended() -> None:
    maintenance = maintenance_from_text(_small("say after laser=running"))
    needs = maintenance.requirements("say")
    assert [str(c) for c in needs.before] == ["laser=running once before say"]
    assert maintenance.plan({"laser": "off", "collision_avoidance": "off", "arm": "parked"},
                            needs) == [("start", "laser"), ("stop", "laser")]
    running = {"laser": "running", "collision_avoidance": "off", "arm": "parked"}
    assert maintenance.plan(running, needs, {"laser=running"}) == [("stop", "laser")]
    assert maintenance.plan({**running, "laser": "off"}, needs, {"laser=running"}) == []


def test_cli_json_gives_the_transformations_and_the_judged_run(
        capsys: pytest.CaptureFixture[str]) -> None:
    import json

    assert main(["golog", "maintain", "rips", "--show", "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert shown["steps"][0]["prefix"] == ["set_posture(arm, unparked)", "start(arm_controller)",
                                           "start(camera)"]
    assert shown["transformed"][3] == "grasp(Registration Sheet)"
    assert main(["golog", "maintain", "rips", "--seed", "5", "--json"]) == 0
    ran = json.loads(capsys.readouterr().out)
    assert ran["success"] and ran["judged"]["violations"] == []


def test_cli_needs_a_section_for_a_domain_without_one(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "maintain", "build_tower(2)", "--domain", "blocks", "--show"]) == 2
    assert "give one with --maintenance FILE" in capsys.readouterr().err
