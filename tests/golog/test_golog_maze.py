"""Maze: solve's value and success probability equal an independent value iteration."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.golog import Interpreter, SimulatedExecutor, State
from homebot.golog.build import do
from homebot.golog.domains import MAZE, maze_theory
from homebot.golog.expressions import Const
from homebot.golog.planner import Planner
from homebot.golog.program import Solve

ORDER = ("go_right", "go_left", "go_up", "go_down")  # the order of the choice in maze.golog
MOVES = {"go_right": (1, 0), "go_left": (-1, 0), "go_up": (0, -1), "go_down": (0, 1)}


class ValueIteration:
    """Finite-horizon value iteration over the maze MDP, written from the grid alone.

    V_0(s) = r(s) with success probability 1; at the goal V_h = r (the loop ends);
    on the stairs nothing is possible: V_h = r, P_h = 0 for h > 0; elsewhere
    V_h(s) = r(s) + max_a Σ p(s'|s,a) V_{h-1}(s'), with DTGolog's comparison
    (a branch with success probability 0 loses to one that can succeed; ties go to
    the later action) and outcomes summed from the last to the first, as DTGolog
    does, so that ties are decided on the same floating-point numbers.
    """

    def __init__(self, rows: tuple[str, ...]) -> None:
        self.rows = rows
        self.cells = [(x, y) for y, row in enumerate(rows) for x, c in enumerate(row)
                      if c != "#"]
        self.index = {cell: i for i, cell in enumerate(self.cells)}
        kinds = {cell: rows[cell[1]][cell[0]] for cell in self.cells}
        self.reward = np.array([100.0 if kinds[c] == "G" else -100.0 if kinds[c] == "X"
                                else -1.0 for c in self.cells])
        self.goal = np.array([kinds[c] == "G" for c in self.cells])
        self.stairs = np.array([kinds[c] == "X" for c in self.cells])

    def _free(self, x: int, y: int) -> bool:
        return 0 <= y < len(self.rows) and 0 <= x < len(self.rows[y]) and \
            self.rows[y][x] != "#"

    def outcomes(self, cell: tuple[int, int], action: str) -> list[tuple[int, float]]:
        dx, dy = MOVES[action]
        merged: dict[int, float] = {}
        for (mx, my), p in (((dx, dy), 0.8), ((dy, dx), 0.1), ((-dy, -dx), 0.1)):
            target = (cell[0] + mx, cell[1] + my)
            if not self._free(*target):
                target = cell
            merged[self.index[target]] = merged.get(self.index[target], 0.0) + p
        return list(merged.items())

    def solve(self, horizon: int) -> tuple[np.ndarray, np.ndarray]:
        values = self.reward.copy()
        success = np.ones(len(self.cells))
        for _ in range(horizon):
            new_values, new_success = self.reward.copy(), np.ones(len(self.cells))
            for i, cell in enumerate(self.cells):
                if self.goal[i]:
                    continue
                if self.stairs[i]:
                    new_success[i] = 0.0
                    continue
                options = []
                for action in ORDER:
                    value = chance = 0.0
                    for j, p in reversed(self.outcomes(cell, action)):
                        value = value + p * values[j]
                        chance = chance + p * success[j]
                    options.append((self.reward[i] + value, chance))
                best = options[-1]
                for option in reversed(options[:-1]):
                    if not _second_is_better(option, best):
                        best = option
                new_values[i], new_success[i] = best
            values, success = new_values, new_success
        return values, success


def _second_is_better(first: tuple[float, float], second: tuple[float, float]) -> bool:
    if first[1] == 0.0:
        return second[1] != 0.0 or first[0] <= second[0]
    return second[1] != 0.0 and first[0] <= second[0]


def _navigate(horizon: int) -> Solve:
    theory = maze_theory()
    body = theory.procedures["navigate"].body.substitute({"H": Const(horizon)})
    assert isinstance(body, Solve)
    return body


@pytest.mark.parametrize("horizon", [1, 3, 8])
def test_value_and_success_probability_match_value_iteration_from_every_cell(
        horizon: int) -> None:
    iteration = ValueIteration(MAZE)
    values, success = iteration.solve(horizon)
    theory = maze_theory()
    solve = _navigate(horizon)
    for cell in iteration.cells:
        state = State({("loc",): cell, ("fallen",): cell in {c for c, s in zip(
            iteration.cells, iteration.stairs, strict=True) if s}})
        result = Planner(theory, solve.reward).solve(solve.body, state, horizon)
        index = iteration.index[cell]
        assert result.value == pytest.approx(values[index], abs=1e-9), cell
        assert result.probability == pytest.approx(success[index], abs=1e-9), cell


def test_the_start_has_a_risky_short_route_the_planner_weighs() -> None:
    theory = maze_theory()
    solve = _navigate(8)
    result = Planner(theory, solve.reward).solve(solve.body, theory.initial, 8)
    assert 0.0 < result.probability < 1.0  # the stairs are next to the short route
    assert result.value > 0.0  # the goal is worth reaching within eight moves


def test_without_memoisation_the_search_finds_the_same_policy() -> None:
    theory = maze_theory()
    solve = _navigate(3)
    first = Planner(theory, solve.reward, memo=True).solve(solve.body, theory.initial, 3)
    second = Planner(theory, solve.reward, memo=False).solve(solve.body, theory.initial, 3)
    assert first == second


@pytest.mark.parametrize("seed", range(6))
def test_stochastic_execution_reaches_the_goal(seed: int) -> None:
    theory = maze_theory()
    executor = SimulatedExecutor(theory, seed=seed)
    run = Interpreter(theory, executor, seed=seed).run(do("reach_goal", 8))
    assert run.success, run.reason
    assert executor.truth.get(("loc",)) == (5, 1)
    assert any(entry["kind"] == "sensed" for entry in run.detail.log)


def test_the_same_seed_gives_the_same_walk() -> None:
    walks = []
    for _ in range(2):
        theory = maze_theory()
        run = Interpreter(theory, SimulatedExecutor(theory, seed=11), seed=11).run(
            do("reach_goal", 8))
        walks.append(run.detail.history)
    assert walks[0] == walks[1]
