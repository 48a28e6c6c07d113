"""The Order Cups Demo (CAESAR Alg. 3): solve re-orders three cups with the fewest moves."""

from __future__ import annotations

import argparse
import random
from typing import Any

from rich.console import Console

from homebot.errors import GologError
from homebot.golog import Interpreter, SimulatedExecutor, State, policy_text
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.scenarios.summary import scenario_summary

__all__ = ["add_arguments", "goal_order", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--goal", default="red,green,blue",
                        help="the cups wanted at p1, p2, p3, comma separated")
    parser.add_argument("--horizon", type=int, default=4, help="horizon of solve")


def goal_order(text: str) -> tuple[str, str, str]:
    """The user's goal order from ``red,green,blue``; anything else raises ``GologError``."""
    cups = tuple(part.strip().lower() for part in text.split(","))
    if sorted(cups) != sorted(CUPS):
        raise GologError(f"--goal '{text}' must name each of {', '.join(CUPS)} once, "
                         f"comma separated, e.g. --goal blue,red,green")
    return cups  # type: ignore[return-value]


def run(args: argparse.Namespace, console: Console | None) -> dict[str, Any]:
    """Cups stand in a seeded order; the robot perceives them, plans, and re-orders them."""
    goal = goal_order(getattr(args, "goal", "red,green,blue"))
    horizon = getattr(args, "horizon", 4)
    rng = random.Random(args.seed)
    initial = dict(zip(CUPS, rng.sample(POSITIONS, len(CUPS)), strict=True))
    theory = cups_theory()
    executor = SimulatedExecutor(theory, seed=args.seed,
                                 truth=State({("pos", cup): at for cup, at in initial.items()}))
    outcome = Interpreter(theory, executor, seed=args.seed).run(
        do("order_cups_demo", *goal, horizon), State())
    moves = [action for action in outcome.history if action[0] == "move_cup"]
    fewest = minimum_moves(initial, goal)
    in_order = all(executor.truth.get(("pos", cup)) == position
                   for cup, position in zip(goal, POSITIONS, strict=False))
    speech = [str(action[1]) for action in outcome.history if action[0] == "say"]
    if console is not None:
        console.print(f"cups at {initial}; wanted at p1, p2, p3: {', '.join(goal)}")
        if outcome.plans:
            console.print(policy_text(outcome.plans[0].policy, markers=False), highlight=False)
        console.print(f"{len(moves)} move{'' if len(moves) == 1 else 's'} (fewest possible: "
                      f"{fewest}); "
                      f"{'in order' if in_order else 'not in order'}")
    return scenario_summary("order_cups", outcome.success and in_order and len(moves) == fewest,
                            outcome.actions, speech, initial=initial, goal=list(goal),
                            moves=len(moves), fewest_moves=fewest, replans=outcome.replans,
                            value=outcome.plans[0].value if outcome.plans else None)
