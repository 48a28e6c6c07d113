"""The online interpreter: IndiGolog's elevator, exogenous actions, waiting, guards, sensing."""

from __future__ import annotations

from typing import Any

import pytest

from homebot.errors import GologError
from homebot.golog import (
    Interpreter,
    SimulatedExecutor,
    State,
    Theory,
    parse_procedures,
    parse_program,
)
from homebot.golog.build import (
    choice,
    conc,
    do,
    eq,
    f,
    if_,
    lt,
    prob,
    proc,
    search,
    seq,
    wait_for,
    while_,
    with_ctrl,
    with_pol,
)
from homebot.golog.build import test as guard
from homebot.golog.domains import elevator_theory


def _served(history: list[tuple[Any, ...]]) -> list[int]:
    return [action[1] for action in history if action[0] == "turnoff"]


def test_the_elevator_serves_every_lit_floor_and_parks() -> None:
    theory = elevator_theory(floors=6, start=3, lit=(2, 5))
    run = Interpreter(theory, SimulatedExecutor(theory)).run(do("control"))
    assert run.success, run.reason
    assert _served(run.detail.history) == [2, 5]
    assert run.detail.state.get(("floor",)) == 1 and run.detail.state.get(("door_open",)) is True
    assert run.detail.actions[:3] == ["down", "turnoff(2)", "open"]


def test_calls_arriving_while_it_runs_are_served_too() -> None:
    theory = elevator_theory(floors=6, start=3, lit=(5,))

    def people(clock: int, truth: State) -> list[tuple[Any, ...]]:
        return [("call", 4)] if clock == 2 else []

    run = Interpreter(theory, SimulatedExecutor(theory, events=people)).run(do("control"))
    assert run.success
    assert sorted(_served(run.detail.history)) == [4, 5]
    assert {"kind": "exogenous", "action": "call(4)"} in run.detail.log


def test_the_alarm_interrupts_with_priority() -> None:
    theory = elevator_theory(floors=6, start=1, lit=(6,))

    def fire(clock: int, truth: State) -> list[tuple[Any, ...]]:
        return [("fire",)] if clock == 2 else []

    run = Interpreter(theory, SimulatedExecutor(theory, events=fire)).run(do("control"))
    assert run.success
    assert run.detail.actions[:4] == ["up", "up", "ring", "reset_alarm"]
    assert _served(run.detail.history) == [6]


def _switch() -> Theory:
    theory = Theory("switch")
    theory.fluent("light", 0, relational=True)
    theory.fluent("count", 0, 0)
    theory.fluent("seen", 0, "nothing")
    theory.action("toggle", effects=lambda s: {("light",): not s.get(("light",), False)})
    theory.action("tick", effects=lambda s: {("count",): s.get(("count",), 0) + 1})
    theory.action("look", senses=lambda: [("seen",)])
    theory.action("press", exogenous=True, effects=lambda s: {("light",): True})
    return theory


def test_wait_for_blocks_until_an_exogenous_action_makes_it_true() -> None:
    theory = _switch()
    executor = SimulatedExecutor(theory, events=lambda clock, truth: [("press",)]
                                 if clock == 3 else [])
    run = Interpreter(theory, executor).run(seq(wait_for(f("light")), "tick"))
    assert run.success and run.detail.actions == ["tick"]
    assert [entry["kind"] for entry in run.detail.log].count("wait") == 3


def test_a_blocked_program_fails_when_nothing_more_will_happen() -> None:
    theory = _switch()
    run = Interpreter(theory, SimulatedExecutor(theory, patience=2)).run(
        wait_for(f("light")))
    assert not run.success and "blocked" in run.reason


def test_with_ctrl_advances_only_while_its_guard_holds() -> None:
    theory = _switch()
    body = while_(lt(f("count"), 5), "tick")
    program = conc(with_ctrl(lt(f("count"), 2), body), seq("toggle", "toggle", "toggle"))
    run = Interpreter(theory, SimulatedExecutor(theory)).run(program)
    assert run.detail.actions[:2] == ["tick", "tick"] and run.detail.actions[2] == "toggle"


def test_with_pol_ends_when_the_program_ends() -> None:
    theory = _switch()
    program = with_pol(seq(wait_for(f("light")), "toggle"), seq("tick", "tick"))
    run = Interpreter(theory, SimulatedExecutor(theory)).run(program)
    assert run.success and run.detail.actions == ["tick", "tick"]


def test_recursive_procedures_run() -> None:
    theory = _switch()
    theory.define(proc("count_to", ["N"], if_(lt(f("count"), "N"),
                                              seq("tick", do("count_to", "N")))))
    run = Interpreter(theory, SimulatedExecutor(theory)).run(do("count_to", 4))
    assert run.success and run.detail.state.get(("count",)) == 4


def test_a_procedure_that_recurses_without_acting_is_an_error() -> None:
    theory = _switch()
    theory.define(*parse_procedures("proc loop loop endproc"))
    with pytest.raises(GologError, match="recurses without ever acting"):
        Interpreter(theory, SimulatedExecutor(theory)).run(do("loop"))


def test_sensing_actions_update_what_the_robot_believes() -> None:
    theory = _switch()
    truth = State({("seen",): "a cat"})
    run = Interpreter(theory, SimulatedExecutor(theory, truth=truth)).run(
        seq("look", if_(eq(f("seen"), "a cat"), "toggle")))
    assert run.success and run.detail.actions == ["look", "toggle"]


def test_prob_is_resolved_by_the_seeded_generator() -> None:
    theory = _switch()
    program = seq(*[prob(0.5, "tick", "toggle") for _ in range(20)])
    runs = [Interpreter(theory, SimulatedExecutor(theory), seed=seed).run(program).detail.actions
            for seed in (5, 5, 6)]
    assert runs[0] == runs[1] and runs[0] != runs[2]
    assert set(runs[0]) == {"tick", "toggle"}


def test_an_action_the_world_refuses_fails_the_run_with_the_reason() -> None:
    theory = _switch()
    theory.action("enter", precondition=f("light"))
    believed_on = State({("light",): True})
    executor = SimulatedExecutor(theory, truth=State())  # in truth the light is off
    run = Interpreter(theory, executor).run(seq("tick", "enter", "tick"), believed_on)
    assert not run.success and run.reason == "enter failed: enter is not possible"
    assert run.detail.situation.history == (("tick",),)


@pytest.mark.parametrize(("text", "words"), [
    ("tick; tock", "'tock' is neither an action"),
    ("tick(3)", "tick(3) has 1 argument(s); 'tick' takes 0"),
    ("?(lihgt(1))", "did you mean 'light'?"),
    ("?(light(1))", "the fluent light(1) has 1 argument(s); 'light' takes 0"),
    ("while not lihgt do tick endwhile", "the condition 'lihgt' is neither"),
    ("pi(x, {1, 2}, ?(x and count = x))", None),
])
def test_programs_are_checked_against_the_theory_before_they_run(text: str,
                                                                 words: str | None) -> None:
    theory = _switch()
    if words is None:  # a bound variable may be tested
        Interpreter(theory, SimulatedExecutor(theory)).run(parse_program(text))
        return
    with pytest.raises(GologError) as raised:
        Interpreter(theory, SimulatedExecutor(theory)).run(parse_program(text))
    assert words in str(raised.value)


def test_the_listener_sees_the_log_as_it_happens_and_history_replays() -> None:
    theory = _switch()
    seen: list[dict[str, Any]] = []
    run = Interpreter(theory, SimulatedExecutor(theory), listener=seen.append).run(
        seq("tick", "toggle", "tick"))
    assert seen == run.detail.log
    assert [entry["action"] for entry in seen] == ["tick", "toggle", "tick"]
    assert theory.state_after(run.detail.situation.history) == run.detail.state


def test_search_looks_ahead_where_plain_choice_commits_blindly() -> None:
    theory = _switch()
    program = seq(choice("tick", "toggle"), guard(f("light")))
    blind = Interpreter(theory, SimulatedExecutor(theory, patience=0)).run(program)
    assert not blind.success and blind.detail.actions == ["tick"]
    looked = Interpreter(theory, SimulatedExecutor(theory)).run(search(program))
    assert looked.success and looked.detail.actions == ["toggle"]


def test_search_finds_the_floor_whose_button_is_lit() -> None:
    theory = elevator_theory(floors=4, start=1, lit=(3,))
    program = parse_program("search(pi(n, floors, go_floor(n); ?(lit(n)); turnoff(n)))")
    run = Interpreter(theory, SimulatedExecutor(theory)).run(program)
    assert run.success and run.detail.actions == ["up", "up", "turnoff(3)"]
