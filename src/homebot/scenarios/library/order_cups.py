"""The Order Cups Demo (CAESAR Alg. 3): solve re-orders three cups with the fewest moves."""

from __future__ import annotations

import argparse
import random
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from rich.console import Console

from homebot.errors import GologError
from homebot.executive import RunReport
from homebot.golog import (
    Executor,
    Interpreter,
    ProgramTrace,
    SimulatedExecutor,
    SkillExecutor,
    State,
    policy_text,
)
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.scenarios.running import OptionKind, RunBuilder, ScenarioRun, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.task import Step
from homebot.world import World

__all__ = ["PLACEMENTS", "SHARED_OPTIONS", "HomeCups", "add_arguments", "goal_order", "home_cups",
           "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),)

#: the four positions as placements of the apartment's kitchen (``--home``)
PLACEMENTS = {"p1": "kitchen table", "p2": "kitchen counter", "p3": "dishwasher",
              "p4": "kitchen cabinet"}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--goal", default="red,green,blue",
                        help="the cups wanted at p1, p2, p3, comma separated")
    parser.add_argument("--horizon", type=int, default=4, help="horizon of solve")
    parser.add_argument("--home", action="store_true",
                        help="run through the skills in the simulated apartment (positions "
                             "are the kitchen table, counter, dishwasher and cabinet)")


def goal_order(text: str) -> tuple[str, str, str]:
    """The user's goal order from ``red,green,blue``; anything else raises ``GologError``."""
    cups = tuple(part.strip().lower() for part in text.split(","))
    if sorted(cups) != sorted(CUPS):
        raise GologError(f"--goal '{text}' must name each of {', '.join(CUPS)} once, "
                         f"comma separated, e.g. --goal blue,red,green")
    return (cups[0], cups[1], cups[2])


@dataclass
class HomeCups:
    """The cups demo wired to the simulated apartment: run, executor, and where cups are."""

    simulated: ScenarioRun
    executor: SkillExecutor

    def truth(self) -> dict[str, str | None]:
        """Where each cup really is, as a position (None: not on any of the four)."""
        positions = {placement: position for position, placement in PLACEMENTS.items()}
        where = self.simulated.simulation.object_location
        return {cup: positions.get(str(where.get(f"{cup} cup"))) for cup in CUPS}


def home_cups(initial: Mapping[str, str], seed: int, build: RunBuilder,
              noticing: Callable[[], list[tuple[Any, ...]]] | None = None) -> HomeCups:
    """The apartment with a red, a green and a blue cup at ``initial`` positions, and a
    skill executor for the cups theory: moves are pick and place, perceiving is looking at
    the four placements; positions are read from the robot's beliefs after each action."""
    data = World.load("apartment").to_dict()
    data["objects"] += [{"name": f"{cup} cup", "category": "dish",
                         "placement": PLACEMENTS[initial[cup]]} for cup in CUPS]
    world = World.from_dict(data, "apartment + three cups")
    simulated = build(world, seed=seed)
    context = simulated.context
    positions = {placement: position for position, placement in PLACEMENTS.items()}

    def believed() -> dict[tuple[Any, ...], Any]:
        return {("pos", cup): positions[str(context.beliefs.object_at.get(f"{cup} cup"))]
                for cup in CUPS
                if str(context.beliefs.object_at.get(f"{cup} cup")) in positions}

    def sensing(action: tuple[Any, ...], done: bool) -> dict[tuple[Any, ...], Any]:
        if not done:  # something is not as planned: look at the table again
            for placement in PLACEMENTS.values():
                simulated.executive.run_step("look", {"placement": placement}, recover=False)
        return believed()

    def move(action: tuple[Any, ...]) -> list[Step]:
        cup = f"{action[1]} cup"
        # pick remembers where it last looked for an object (for its retries) and never
        # forgets it; a cup picked again from elsewhere must be looked for where it is now.
        context.bindings.pop(f"placement:{cup}", None)
        return [Step("pick", {"object": cup}),
                Step("place", {"placement": PLACEMENTS[action[3]], "object": cup})]

    bindings = {
        "perceive_cups": lambda action: [Step("look", {"placement": placement})
                                         for placement in PLACEMENTS.values()],
        "move_cup": move,
        "say": lambda action: [Step("say", {"text": str(action[1])})],
    }
    # a cup not where the plan put it is the program's to re-plan, not a search's
    executor = SkillExecutor(simulated.executive, bindings, sensing=sensing, noticing=noticing,
                             recover=False)
    return HomeCups(simulated, executor)


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Cups stand in a seeded order; the robot perceives them, plans, and re-orders them."""
    goal = goal_order(getattr(args, "goal", "red,green,blue"))
    horizon = getattr(args, "horizon", 4)
    rng = random.Random(args.seed)
    initial = dict(zip(CUPS, rng.sample(POSITIONS, len(CUPS)), strict=True))
    theory = cups_theory()
    executor: Executor
    figures: dict[str, Any] = {}
    if getattr(args, "home", False):
        home = home_cups(initial, args.seed, build)
        executor = home.executor
        outcome: RunReport[ProgramTrace] = Interpreter(theory, executor, seed=args.seed).run(
            do("order_cups_demo", *goal, horizon), State())
        final = home.truth()
        figures = {"skills": home.executor.steps,
                   "sim_time": round(home.simulated.robot.now(), 2)}
    else:
        simulated = SimulatedExecutor(theory, seed=args.seed, truth=State(
            {("pos", cup): at for cup, at in initial.items()}))
        executor = simulated
        outcome = Interpreter(theory, executor, seed=args.seed).run(
            do("order_cups_demo", *goal, horizon), State())
        final = {cup: simulated.truth.get(("pos", cup)) for cup in CUPS}
    moves = [action for action in outcome.detail.history if action[0] == "move_cup"]
    fewest = minimum_moves(initial, goal)
    in_order = all(final[cup] == position for cup, position in zip(goal, POSITIONS,
                                                                    strict=False))
    speech = [str(action[1]) for action in outcome.detail.history if action[0] == "say"]
    if console is not None:
        console.print(f"cups at {initial}; wanted at p1, p2, p3: {', '.join(goal)}")
        if outcome.detail.plans:
            console.print(policy_text(outcome.detail.plans[0].policy, markers=False),
                          highlight=False)
        console.print(f"{len(moves)} move{'' if len(moves) == 1 else 's'} (fewest possible: "
                      f"{fewest}); {'in order' if in_order else 'not in order'}"
                      f"{': ' + outcome.reason if outcome.reason else ''}")
    return scenario_summary("order_cups", outcome.success and in_order and len(moves) == fewest,
                            outcome.detail.actions, speech, initial=initial, goal=list(goal),
                            moves=len(moves), fewest_moves=fewest, replans=outcome.detail.replans,
                            value=outcome.detail.plans[0].value if outcome.detail.plans else None,
                            **figures)
