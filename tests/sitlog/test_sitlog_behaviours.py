"""Behaviours as dialogue models over the skills: move (with recovery), take, find."""

from __future__ import annotations

from typing import Any

from homebot.app import Run, RunSettings, build_run
from homebot.sitlog import Interpreter, Var, format_term, load_program, parse_term
from homebot.sitlog.robot import SkillBody, SkillPerception
from homebot.sitlog.terms import resolve
from homebot.world import DoorState, World


def _home() -> World:
    return World.load("butler_home")


def _call(world: World, call: str,
          shut: tuple[str, ...] = ()) -> tuple[dict[str, Var], Any, Run]:
    run = build_run(RunSettings(world=world, seed=1))
    for door in shut:  # shut while the robot was not looking: it believes the door open
        run.simulation.door_state[door] = DoorState.CLOSED
    variables: dict[str, Var] = {}
    term = parse_term(call, "<test>", variables)
    result = Interpreter(load_program("behaviours"), SkillPerception(run.executive),
                         body=SkillBody(run.executive), application=run.context).run(term)
    return variables, result, run


def test_move_opens_a_closed_door_on_the_way() -> None:
    variables, result, run = _call(_home(), "move('toy box', Status)", shut=("kids room door",))
    assert resolve(variables["Status"]) == "ok"
    situations = [format_term(t.situation) for t in result.detail.transitions()]
    assert situations[:3] == ["is", "open('kids room door')", "is"]
    assert run.simulation.door_state["kids room door"].value == "open"


def test_take_is_approach_and_grasp_with_the_arm_given() -> None:
    variables, _, run = _call(_home(), "take(malz, shelf_drinks, right, Status)")
    assert resolve(variables["Status"]) == "ok"
    assert run.simulation.hands["right"] == "malz"


def test_take_ends_with_the_error_status_when_the_object_is_not_there() -> None:
    variables, _, run = _call(_home(), "take(malz, shelf_food, left, Status)")
    assert resolve(variables["Status"]) == "not_found"
    assert run.simulation.hands["left"] is None


def test_find_scans_placements_in_order() -> None:
    variables, result, _ = _call(_home(), "find(noodles, [shelf_food, shelf_snacks], Where)")
    assert resolve(variables["Where"]) == "shelf_snacks"
    assert format_term(result.detail.final) == "ok"
    variables, result, _ = _call(_home(), "find(noodles, [shelf_food], Where)")
    assert resolve(variables["Where"]) == "none"
    assert format_term(result.detail.final) == "not_found"


def test_move_asks_someone_in_the_doorway_to_let_it_through() -> None:
    run = build_run(RunSettings(world=_home(), seed=1))
    run.simulation.place_person_in_doorway("kids room door", "Tom")
    variables: dict[str, Var] = {}
    term = parse_term("move('toy box', Status)", "<test>", variables)
    body = SkillBody(run.executive)
    Interpreter(load_program("behaviours"), SkillPerception(run.executive), body=body,
                application=run.context).run(term)
    assert resolve(variables["Status"]) == "ok"
    said = [event.data["text"] for event in run.simulation.events.of_kind("speech")]
    assert said == ["Excuse me, Tom, could you please let me through?", "Thank you!"]


def test_take_then_deliver_to_a_person() -> None:
    run = build_run(RunSettings(world=_home(), seed=2))
    variables: dict[str, Var] = {}
    program = load_program("behaviours")
    perception, body = SkillPerception(run.executive), SkillBody(run.executive)
    for call in ("take(malz, shelf_drinks, left, Took)", "deliver(malz, 'Luis', 'living room', S)"):
        Interpreter(program, perception, body=body, application=run.context).run(
            parse_term(call, "<test>", variables))
    assert resolve(variables["Took"]) == "ok" and resolve(variables["S"]) == "ok"
    assert run.simulation.object_location["malz"] == "person:Luis"
