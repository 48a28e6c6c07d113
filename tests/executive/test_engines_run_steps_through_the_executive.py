"""HTN, Golog and SitLog tasks run their skills through ``Executive.run_step``: a door shut
on their way gets the executive's door protocol, and the task's time budget stops them."""

from __future__ import annotations

from typing import Any

import homebot.app as app
from homebot.app import RunSettings, build_run
from homebot.events import EventLog
from homebot.executive import RunReport
from homebot.golog import Interpreter, ProgramTrace, State, Theory, parse_program
from homebot.golog.skill_executor import SkillExecutor
from homebot.htn import Goal, HtnTrace, Names, PlanActor, home_domain
from homebot.sitlog import DialogueTrace, Var, format_term, load_program, parse_term
from homebot.sitlog import Interpreter as DialogueInterpreter
from homebot.sitlog.robot import SkillBody, SkillPerception
from homebot.sitlog.terms import resolve
from homebot.task import Step
from homebot.world import DoorState, World


def _shut(world: World, door: str, time_limit: float | None) -> app.Run:
    """A run whose robot believes ``door`` open: it was shut while the robot was away."""
    run = build_run(RunSettings(world=world, time_limit=time_limit))
    run.simulation.door_state[door] = DoorState.CLOSED
    return run


def _door_opened_by_the_executive(events: EventLog, door: str, run: app.Run) -> bool:
    recovered = [event.data["error"] for event in events.of_kind("recovery")]
    opened = [event.data["status"] for event in events.of_kind("skill.status")
              if event.data["skill"] == "open_door"]
    return (recovered == ["door_closed"] and opened[-1:] == ["verified"]
            and run.simulation.door_state[door] is DoorState.OPEN)


def _started_after(events: EventLog, deadline: float) -> list[str]:
    return [event.data["skill"] for event in events.of_kind("skill.start")
            if event.time > deadline]


# -- HTN: guide Alex to the bedroom, whose door is shut -------------------------------------

def _guide_alex(apartment: World,
                time_limit: float | None) -> tuple[app.Run, RunReport[HtnTrace]]:
    run = _shut(apartment, "bedroom door", time_limit)
    names, domain = Names(), home_domain()
    goal = Goal.of("guide_person", ["Alex", "bedroom"], apartment, names, domain)
    return run, PlanActor(run.executive, domain).run(goal, names)


def _recovered(report: RunReport[Any]) -> list[tuple[str, tuple[str, ...]]]:
    """The steps of the run's report that went through recovery, with what was mended."""
    return [(step.skill, step.recoveries) for step in report.steps if step.recoveries]


def test_an_htn_plan_gets_the_door_protocol(apartment: World) -> None:
    run, done = _guide_alex(apartment, None)
    assert done
    assert _door_opened_by_the_executive(run.simulation.events, "bedroom door", run)
    assert _recovered(done) == [("guide", ("door_closed",))]


def test_an_htn_plan_stops_at_the_time_budget_without_replanning(apartment: World) -> None:
    # 35 s: enough to guide Alex through the opened door, not to report it afterwards.
    run, done = _guide_alex(apartment, 35.0)
    events = run.simulation.events
    assert _door_opened_by_the_executive(events, "bedroom door", run)
    assert not done
    last = done.detail.operators[-1]
    assert (last.operator, last.error) == ("!report", "out_of_time")
    assert done.detail.replans == 0
    assert "ran out of time" in done.reason
    assert _started_after(events, 35.0) == []


# -- Golog: a program that drives to the bed (behind the shut door), then to the desk ------

def _errand(apartment: World,
            time_limit: float | None) -> tuple[app.Run, RunReport[ProgramTrace]]:
    run = _shut(apartment, "bedroom door", time_limit)
    theory = Theory("errand")
    theory.action("goto", ["place"])
    executor = SkillExecutor(run.executive,
                             {"goto": lambda action: [Step("navigate", {"to": str(action[1])})]})
    program = parse_program("goto(bed); goto(desk)", "<test>")
    return run, Interpreter(theory, executor).run(program, State())


def test_a_golog_program_gets_the_door_protocol(apartment: World) -> None:
    run, done = _errand(apartment, None)
    assert done
    assert _door_opened_by_the_executive(run.simulation.events, "bedroom door", run)
    assert _recovered(done) == [("navigate", ("door_closed",))]


def test_a_golog_program_stops_at_the_time_budget(apartment: World) -> None:
    # 20 s: enough to open the door and reach the bed, not to set off for the desk.
    run, done = _errand(apartment, 20.0)
    events = run.simulation.events
    assert _door_opened_by_the_executive(events, "bedroom door", run)
    assert not done
    assert done.detail.actions == ["goto(bed)"]
    assert "ran out of time" in done.reason
    assert _started_after(events, 20.0) == []


# -- SitLog: find the noodles in the toy box (behind the shut kids room door), then the shelf

_FIND = "find(noodles, ['toy box', shelf_snacks], Where)"


def _find_noodles(
        time_limit: float | None) -> tuple[app.Run, RunReport[DialogueTrace], Var]:
    run = _shut(World.load("butler_home"), "kids room door", time_limit)
    variables: dict[str, Var] = {}
    call = parse_term(_FIND, "<test>", variables)
    result = DialogueInterpreter(load_program("behaviours"), SkillPerception(run.executive),
                                 body=SkillBody(run.executive), application=run.context,
                                 executive=run.executive).run(call)
    return run, result, variables["Where"]


def test_a_sitlog_dialogue_gets_the_door_protocol() -> None:
    run, result, where = _find_noodles(None)
    # The model's look situation names no door: the executive opened it, the look went on.
    assert _door_opened_by_the_executive(run.simulation.events, "kids room door", run)
    assert result and format_term(result.detail.final) == "ok"
    assert resolve(where) == "shelf_snacks"
    assert _recovered(result) == [("look", ("door_closed",))]


def test_a_sitlog_dialogue_stops_at_the_time_budget() -> None:
    # 15 s: enough to open the door and look into the toy box, not to go to the shelf.
    run, result, where = _find_noodles(15.0)
    events = run.simulation.events
    assert _door_opened_by_the_executive(events, "kids room door", run)
    assert format_term(result.detail.final) == "stopped(out_of_time)"
    assert not result and "ran out of time" in result.reason
    assert isinstance(resolve(where), Var)
    assert _started_after(events, 15.0) == []
