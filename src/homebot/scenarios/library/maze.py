"""Maze navigation with stochastic moves (CAESAR Fig. 5): solve, run the policy, plan again."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.errors import GologError
from homebot.golog import Interpreter, SimulatedExecutor
from homebot.golog.build import do
from homebot.golog.domains import Maze, maze_theory
from homebot.scenarios.running import RunBuilder
from homebot.scenarios.summary import scenario_summary

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--horizon", type=int, default=8, help="horizon of each solve")


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """From S to G; moves slip sideways with probability 0.2; falling down the stairs fails."""
    horizon = getattr(args, "horizon", 8)
    if horizon < 1:
        raise GologError(f"--horizon {horizon}: give 1 or more (at 0 the robot plans no move)")
    maze = Maze()
    theory = maze_theory(maze)
    executor = SimulatedExecutor(theory, seed=args.seed)
    outcome = Interpreter(theory, executor, seed=args.seed).run(do("reach_goal", horizon))
    at = executor.truth.get(("loc",), maze.start)
    reached = at == maze.goal
    first = outcome.detail.plans[0] if outcome.detail.plans else None
    if console is not None:
        visited = {maze.start} | {(a[1], a[2]) for a in _arrivals(outcome.detail.log)}
        for y, row in enumerate(maze.rows):
            console.print("".join("*" if (x, y) in visited and char == "." else char
                                  for x, char in enumerate(row)), highlight=False)
        if first is not None:
            console.print(f"first policy: value {first.value:.4f}, success probability "
                          f"{first.probability:.4f}")
        fell = at in maze.stairs
        console.print(f"{'reached the goal' if reached else 'did not reach the goal'} after "
                      f"{len(outcome.detail.history)} moves and {len(outcome.detail.plans)} plans"
                      f"{' (it slipped and fell down the stairs)' if fell else ''}")
    return scenario_summary("maze", outcome.success and reached, outcome.detail.actions, [],
                            moves=len(outcome.detail.history), plans=len(outcome.detail.plans),
                            value=first.value if first else None,
                            success_probability=first.probability if first else None,
                            end=list(at), fell=at in maze.stairs)


def _arrivals(log: list[dict[str, Any]]) -> list[tuple[Any, ...]]:
    found = []
    for entry in log:
        if entry["kind"] == "sensed" and entry["outcome"].startswith("arrive("):
            x, y = entry["outcome"][len("arrive("):-1].split(", ")
            found.append(("arrive", int(x), int(y)))
    return found
