"""Golog ``solve``: Order Cups at horizon 4 and the maze at horizon 8 (nodes per second, time)."""

from __future__ import annotations

import argparse
import itertools
import time
from typing import Any

from rich.console import Console

from homebot.bench.arguments import count
from homebot.golog import State
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, maze_theory
from homebot.golog.expressions import Const
from homebot.golog.planner import Planner
from homebot.golog.program import Call, Program, Solve
from homebot.golog.semantics import unfold
from homebot.golog.theory import Theory
from homebot.progress import track

__all__ = ["add_arguments", "run"]

#: the arrangement that needs the most moves (a 3-cycle with the fourth position free)
HARDEST = {"red": "p2", "green": "p3", "blue": "p1"}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeats", type=count("--repeats", 1, 1000), default=5,
                        help="timed runs per figure")
    # Horizons grow the search exponentially: the maze at 20 takes gigabytes.
    parser.add_argument("--maze-horizon", type=count("--maze-horizon", 1, 12), default=8)
    parser.add_argument("--cups-horizon", type=count("--cups-horizon", 1, 6), default=4)


def _solve_of(theory: Theory, call: Call) -> Solve:
    body: Program = unfold(call, theory, theory.initial)
    assert isinstance(body, Solve)
    return body


def _measure(theory: Theory, solve: Solve, horizon: int, state: State, memo: bool,
             repeats: int) -> dict[str, Any]:
    best = float("inf")
    nodes = 0
    result = None
    for _ in range(repeats):
        planner = Planner(theory, solve.reward, memo=memo)
        began = time.perf_counter()
        result = planner.solve(solve.body, state, horizon)
        best = min(best, time.perf_counter() - began)
        nodes = planner.nodes
    assert result is not None
    return {"memo": memo, "horizon": horizon, "nodes": nodes,
            "wall_ms": round(1000 * best, 3), "nodes_per_second": round(nodes / best),
            "value": round(result.value, 9), "success_probability": round(result.probability, 9)}


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Best-of-N wall time and nodes expanded, with and without memoisation where feasible."""
    repeats = max(1, getattr(args, "repeats", 5))
    cups_horizon = getattr(args, "cups_horizon", 4)
    maze_horizon = getattr(args, "maze_horizon", 8)
    figures: dict[str, Any] = {}
    theory = cups_theory(HARDEST)
    solve = _solve_of(theory, Call("sort_cups", (*map(Const, CUPS), Const(cups_horizon))))
    for memo in (False, True):
        figures[f"order cups, hardest start, memo {'on' if memo else 'off'}"] = _measure(
            theory, solve, cups_horizon, theory.initial, memo, repeats)
    starts = [cups_theory(dict(zip(CUPS, places, strict=True)))
              for places in itertools.permutations(POSITIONS, len(CUPS))]
    for memo in track((False, True), "order cups, all 24 starts, memo off and on"):
        began, nodes = time.perf_counter(), 0
        for start in starts:
            planner = Planner(start, solve.reward, memo=memo)
            planner.solve(solve.body, start.initial, cups_horizon)
            nodes += planner.nodes
        seconds = time.perf_counter() - began
        figures[f"order cups, all 24 starts, memo {'on' if memo else 'off'}"] = {
            "memo": memo, "horizon": cups_horizon, "nodes": nodes,
            "wall_ms": round(1000 * seconds, 3), "nodes_per_second": round(nodes / seconds)}
    maze = maze_theory()
    navigate = _solve_of(maze, Call("navigate", (Const(maze_horizon),)))
    figures["maze, memo on"] = _measure(maze, navigate, maze_horizon, maze.initial, True,
                                        repeats)
    small = min(maze_horizon, 4)
    figures[f"maze, memo off (horizon {small}: horizon 8 is ~12^4 times more)"] = _measure(
        maze, _solve_of(maze, Call("navigate", (Const(small),))), small, maze.initial, False,
        1)
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}", highlight=False)
    return {"benchmark": "golog", "repeats": repeats, "figures": figures}
