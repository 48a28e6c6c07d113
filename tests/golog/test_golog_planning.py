"""``solve`` follows DTGolog: values, success probabilities, comparison and tie rules, markers."""

from __future__ import annotations

import pytest

from homebot.errors import GologError
from homebot.golog import State, Theory, parse_program, plan, policy_actions, policy_text
from homebot.golog.build import (
    choice,
    conc,
    const,
    do,
    eq,
    f,
    pi,
    pproj,
    prob,
    seq,
    solve,
    star,
    wait_for,
)
from homebot.golog.build import test as guard
from homebot.golog.domains import blocks_theory
from homebot.golog.planner import Planner, better_second, project
from homebot.golog.policy import PDo, PMarker, PStop, Result


def _counter() -> Theory:
    """``n`` counts up; ``bump`` adds one, ``reset`` sets zero; ``flip`` is a fair coin."""
    theory = Theory("counter")
    theory.fluent("n", 0, 0)
    theory.fluent("heads", 0, relational=True)
    theory.function("reward", lambda state: float(state.get(("n",), 0)))
    theory.action("bump", effects=lambda s: {("n",): s.get(("n",), 0) + 1})
    theory.action("reset", effects=lambda s: {("n",): 0})
    theory.action("never", precondition=lambda s: False)
    theory.stochastic("flip", outcomes=lambda s: [(("land", True), 0.5), (("land", False), 0.5)])
    theory.action("land", ("side",), effects=lambda s, side: {("heads",): side},
                  sense=eq(f("heads"), "side"))
    return theory


def test_blocksworld_policy_is_c_to_the_table_then_b_on_a_then_c_on_b() -> None:
    theory = blocks_theory()
    program = parse_program("build_tower(4)")
    result = plan(theory, _only_solve(theory, program), theory.initial)
    assert policy_actions(result.policy) == [("stack", "c", "table"), ("stack", "b", "a"),
                                             ("stack", "c", "b")]
    assert result.probability == 1.0
    assert result.value == 10.0 - 3


def _only_solve(theory: Theory, program: object) -> object:
    from homebot.golog.program import Call
    from homebot.golog.semantics import unfold

    assert isinstance(program, Call)
    return unfold(program, theory, theory.initial)


@pytest.mark.parametrize(("first", "second", "second_wins"), [
    (Result(5.0, 0.0, PStop()), Result(1.0, 0.5, PStop()), True),  # can fail vs can succeed
    (Result(1.0, 0.5, PStop()), Result(5.0, 0.0, PStop()), False),
    (Result(1.0, 0.5, PStop()), Result(2.0, 0.1, PStop()), True),  # higher value wins
    (Result(3.0, 0.5, PStop()), Result(3.0, 0.9, PStop()), True),  # ties: the later branch
    (Result(3.0, 0.0, PStop()), Result(3.0, 0.0, PStop()), True),
    (Result(4.0, 0.0, PStop()), Result(3.0, 0.0, PStop()), False),
])
def test_dtgolog_comparison(first: Result, second: Result, second_wins: bool) -> None:
    assert better_second(first, second) is second_wins


def test_value_adds_the_reward_of_every_situation_passed() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(seq("bump", "bump", "bump"), State(), 5)
    assert result.value == 0 + 1 + 2 + 3 and result.probability == 1.0


def test_the_horizon_cuts_the_program_short_with_success_probability_one() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(seq("bump", "bump", "bump"), State(), 2)
    assert result.value == 0 + 1 + 2 and result.probability == 1.0


def test_an_impossible_action_stops_with_probability_zero_and_a_false_marker() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(seq("bump", "never", "bump"), State(), 5)
    assert result.probability == 0.0 and result.value == 0 + 1
    assert "M(poss(never), false)" in policy_text(result.policy)


def test_choice_prefers_what_can_succeed_over_a_higher_value() -> None:
    theory = _counter()
    program = choice(seq("bump", "bump", "never"), "bump")
    result = Planner(theory, f("reward")).solve(program, State(), 5)
    assert policy_actions(result.policy) == [("bump",)] and result.probability == 1.0


def test_star_and_pi_are_optimised_within_the_horizon() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(star(choice("bump", "reset")), State(), 3)
    assert policy_actions(result.policy) == [("bump",)] * 3
    picked = Planner(theory, f("reward")).solve(
        pi("k", [1, 2, 3], seq("bump", "bump", guard(eq(f("n"), "k")))), State(), 5)
    assert picked.probability == 1.0
    assert "M(n = 2, true)" in policy_text(picked.policy)


def test_stochastic_actions_branch_on_sensing_conditions() -> None:
    theory = _counter()
    program = seq("flip", choice(seq(guard(f("heads")), "bump"), guard(~f("heads"))))
    result = Planner(theory, f("reward")).solve(program, State(), 3)
    assert result.probability == 1.0
    assert result.value == pytest.approx(0 + 0.5 * (0 + 1) + 0.5 * 0)
    text = policy_text(result.policy)
    assert "senseEffect(flip)" in text and "heads = true" in text


def test_a_long_policy_text_is_cut_and_says_so() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(seq("flip", "flip", "flip"), State(), 3)
    whole = policy_text(result.policy).splitlines()
    cut = policy_text(result.policy, limit=5).splitlines()
    assert len(whole) > 6 and cut[:5] == whole[:5] and len(cut) == 6
    assert cut[5].startswith("... (cut after 5 lines")
    assert policy_text(result.policy, limit=len(whole)).splitlines() == whole


def test_prob_weighs_two_programs() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(prob(0.25, seq("bump", "bump"), "never"),
                                                State(), 5)
    assert result.probability == pytest.approx(0.25)
    assert result.value == pytest.approx(0.25 * 3 + 0.75 * 0)


def test_pproj_is_the_probability_a_condition_holds_after_a_program() -> None:
    theory = _counter()
    assert project(theory, seq("flip", "flip"), State(), f("heads")) == pytest.approx(0.5)
    assert project(theory, prob(0.3, "bump", "nil"), State(), eq(f("n"), 1)) == pytest.approx(
        0.3)
    assert theory.holds(eq(pproj(eq(f("n"), 2), seq("bump", "bump")), 1.0), State())


def test_the_first_marker_records_the_loop_test_and_the_precondition() -> None:
    theory = blocks_theory()
    result = plan(theory, _only_solve(theory, parse_program("build_tower(4)")), theory.initial)
    policy = result.policy
    assert isinstance(policy, PMarker) and policy.value is True
    assert isinstance(policy.then, PMarker) and str(policy.then.condition) == (
        "poss(stack(c, table))")
    assert isinstance(policy.then.then, PDo)


def test_a_bad_horizon_is_an_error_a_person_can_fix() -> None:
    theory = _counter()
    with pytest.raises(GologError, match="whole number"):
        plan(theory, solve(const("four"), f("reward"), "bump"), State())


def test_an_unknown_action_is_named() -> None:
    theory = _counter()
    with pytest.raises(GologError, match="'jump' is not an action"):
        Planner(theory, f("reward")).solve(do("jump"), State(), 2)


def test_concurrency_and_waiting_inside_solve_follow_the_transition_semantics() -> None:
    theory = _counter()
    result = Planner(theory, f("reward")).solve(
        conc(seq("bump", "bump"), "reset"), State(), 5)
    assert policy_actions(result.policy)[:2] == [("bump",), ("bump",)]  # priority goes first
    blocked = Planner(theory, f("reward")).solve(wait_for(f("heads")), State(), 5)
    assert blocked.probability == 0.0 and isinstance(blocked.policy, PStop)


def test_progression_changes_only_what_an_action_affects() -> None:
    theory = _counter()
    start = State({("heads",): True, ("n",): 4})
    after = theory.do(("reset",), start)
    assert after.get(("n",)) == 0 and after.get(("heads",)) is True
    assert start.get(("n",)) == 4  # states are values: the old one is unchanged


def test_chance_and_a_nested_solve_inside_concurrency_are_planned() -> None:
    theory = _counter()
    mixed = Planner(theory, f("reward")).solve(
        conc(prob(0.5, "bump", "never"), wait_for(f("heads"))), State(), 3)
    assert mixed.probability == pytest.approx(0.5)
    nested = Planner(theory, f("reward")).solve(
        conc(solve(2, f("reward"), seq("bump", "bump")), wait_for(f("heads"))), State(), 3)
    assert policy_actions(nested.policy) == [("bump",), ("bump",)]
