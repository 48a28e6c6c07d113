"""Order Cups: every initial arrangement and goal order is sorted with the fewest moves."""

from __future__ import annotations

import itertools

import pytest

from homebot.golog import Interpreter, SimulatedExecutor, State, policy_actions
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.golog.expressions import Const
from homebot.golog.planner import Planner
from homebot.golog.program import Call, Solve
from homebot.golog.semantics import unfold

ARRANGEMENTS = [dict(zip(CUPS, places, strict=True))
                for places in itertools.permutations(POSITIONS, len(CUPS))]
GOALS = list(itertools.permutations(CUPS))


def test_there_are_24_arrangements_with_a_free_fourth_position() -> None:
    assert len(ARRANGEMENTS) == 24
    assert len({tuple(sorted(a.values())) for a in ARRANGEMENTS}) == 4


@pytest.mark.parametrize("goal", GOALS, ids="-".join)
def test_the_executed_policy_uses_the_fewest_moves_for_every_arrangement(
        goal: tuple[str, str, str]) -> None:
    for initial in ARRANGEMENTS:
        theory = cups_theory()
        truth = State({("pos", cup): at for cup, at in initial.items()})
        executor = SimulatedExecutor(theory, truth=truth)
        run = Interpreter(theory, executor).run(do("order_cups_demo", *goal, 4), State())
        moves = [action for action in run.detail.history if action[0] == "move_cup"]
        assert run.success, (initial, goal, run.reason)
        assert len(moves) == minimum_moves(initial, goal), (initial, goal, moves)
        assert [executor.truth.get(("pos", cup)) for cup in goal] == list(POSITIONS[:3])
        assert run.detail.history[0] == ("perceive_cups",)
        assert run.detail.history[-1] == ("say", "That is it. I am done.")


def test_the_brute_force_agrees_with_hand_counts() -> None:
    goal = ("red", "green", "blue")
    assert minimum_moves({"red": "p1", "green": "p2", "blue": "p3"}, goal) == 0
    assert minimum_moves({"red": "p2", "green": "p3", "blue": "p1"}, goal) == 4
    assert minimum_moves({"red": "p4", "green": "p2", "blue": "p3"}, goal) == 1
    assert max(minimum_moves(a, goal) for a in ARRANGEMENTS) == 4


def _sort_cups(goal: tuple[str, ...], horizon: int) -> Solve:
    theory = cups_theory()
    body = unfold(Call("sort_cups", (*map(Const, goal), Const(horizon))), theory, State())
    assert isinstance(body, Solve)
    return body


def test_the_policy_value_counts_moves_and_marks_each_precondition() -> None:
    theory = cups_theory({"red": "p2", "green": "p3", "blue": "p1"})
    solve = _sort_cups(("red", "green", "blue"), 4)
    result = Planner(theory, solve.reward).solve(solve.body, theory.initial, 4)
    assert result.value == 10.0 - 4 and result.probability == 1.0
    assert len(policy_actions(result.policy)) == 4


def test_a_horizon_too_short_gives_a_policy_that_does_not_sort() -> None:
    theory = cups_theory({"red": "p2", "green": "p3", "blue": "p1"})
    solve = _sort_cups(("red", "green", "blue"), 3)
    result = Planner(theory, solve.reward).solve(solve.body, theory.initial, 3)
    assert result.value == -4.0  # four unsorted situations, none sorted


def test_memoisation_changes_the_work_not_the_answer() -> None:
    for initial in ARRANGEMENTS[:8]:
        theory = cups_theory(initial)
        solve = _sort_cups(("blue", "red", "green"), 4)
        with_memo = Planner(theory, solve.reward, memo=True)
        without = Planner(theory, solve.reward, memo=False)
        first = with_memo.solve(solve.body, theory.initial, 4)
        second = without.solve(solve.body, theory.initial, 4)
        assert first == second
        assert with_memo.nodes <= without.nodes


def test_a_cup_moved_by_a_person_breaks_a_marker_and_the_robot_replans() -> None:
    start = {"red": "p2", "green": "p3", "blue": "p1"}
    theory = cups_theory(start)

    def person(clock: int, truth: State) -> list[tuple[str, ...]]:
        # After the robot's first move (blue to p4), someone puts green into p1.
        return [("person_moves_cup", "green", "p1")] if clock == 1 else []

    executor = SimulatedExecutor(theory, events=person)
    run = Interpreter(theory, executor).run(do("sort_cups", "red", "green", "blue", 4))
    assert run.success
    replans = [entry for entry in run.detail.log if entry["kind"] == "replan"]
    assert replans and replans[0]["marker"].startswith("poss(move_cup(red")
    assert len(run.detail.plans) == 2
    # after the disturbance the robot again uses the fewest moves
    after = {"red": "p2", "green": "p1", "blue": "p4"}
    assert len(run.detail.history) - 1 == minimum_moves(after, ("red", "green", "blue"))
    assert [executor.truth.get(("pos", c)) for c in ("red", "green", "blue")] == [
        "p1", "p2", "p3"]


def test_an_unseen_move_is_found_by_sensing_or_by_the_failed_action() -> None:
    start = {"red": "p2", "green": "p3", "blue": "p1"}
    theory = cups_theory(start)

    def person(clock: int, truth: State) -> list[tuple[str, ...]]:
        return [("person_moves_cup", "green", "p1")] if clock == 1 else []

    executor = SimulatedExecutor(theory, events=person, observed=False)
    run = Interpreter(theory, executor).run(do("sort_cups", "red", "green", "blue", 4))
    assert run.success
    assert not any(entry["kind"] == "exogenous" for entry in run.detail.log)  # never seen happening
    failed = [entry for entry in run.detail.log if entry["kind"] == "action" and not entry["ok"]]
    assert [entry["action"] for entry in failed] == ["move_cup(red, p2, p1)"]
    replans = [entry for entry in run.detail.log if entry["kind"] == "replan"]
    assert [entry["marker"] for entry in replans] == ["done(move_cup(red, p2, p1))"]
    assert [executor.truth.get(("pos", c)) for c in ("red", "green", "blue")] == [
        "p1", "p2", "p3"]


def test_a_move_that_keeps_failing_ends_the_run_after_the_replan_budget() -> None:
    theory = cups_theory({"red": "p2", "green": "p3", "blue": "p1"})
    glued = cups_theory({"red": "p2", "green": "p3", "blue": "p1"})
    glued.action("move_cup", ("cup", "from", "to"), precondition=lambda *_: False)
    executor = SimulatedExecutor(glued)  # the world refuses every move: the cups are glued
    run = Interpreter(theory, executor, max_replans=3).run(
        do("sort_cups", "red", "green", "blue", 4))
    assert not run.success and "not possible" in run.reason
    assert run.detail.replans == 3
