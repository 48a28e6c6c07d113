"""A person moves a cup mid-execution; the policy's marker notices and the robot re-plans."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.errors import GologError
from homebot.golog import Executor, Interpreter, SimulatedExecutor, State
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.scenarios.library.order_cups import PLACEMENTS, home_cups
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary

__all__ = ["SHARED_OPTIONS", "add_arguments", "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),)

#: the cups' start (a 3-cycle: four moves) and the goal order
START = {"red": "p2", "green": "p3", "blue": "p1"}
GOAL = ("red", "green", "blue")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--after", type=int, default=1,
                        help="how many robot actions before the person moves a cup")
    parser.add_argument("--unseen", action="store_true",
                        help="the robot does not see the person move the cup: it finds out "
                             "by looking at the table as it moves the next one")
    parser.add_argument("--home", action="store_true",
                        help="run through the skills in the simulated apartment")


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """The person puts the red cup into the free position after the robot's first move.

    Seen, the exogenous action updates the robot's model at once and the next
    marker fails; unseen, the robot learns of it by sensing the table during its
    next move (or that move fails), and the policy's markers fail then.
    """
    after = getattr(args, "after", 1)
    if after < 0:
        raise GologError(f"--after {after}: give how many moves the robot makes first, 0 or more")
    unseen = getattr(args, "unseen", False)
    theory = cups_theory(START)
    moved: list[tuple[Any, ...]] = []

    def person(clock: int, truth: State) -> list[tuple[Any, ...]]:
        if clock != after or moved:
            return []
        free = [p for p in POSITIONS if p not in {truth.get(("pos", c)) for c in CUPS}]
        cup = "red" if truth.get(("pos", "red")) != POSITIONS[0] else "green"
        moved.append(("person_moves_cup", cup, free[0]))
        return list(moved)

    executor: Executor
    figures: dict[str, Any] = {}
    if getattr(args, "home", False):
        seen: list[tuple[Any, ...]] = []

        def noticing() -> list[tuple[Any, ...]]:
            # After the robot's move number ``after``, a person moves a cup in the home.
            done = sum(1 for step in home.executor.steps if step["skill"] == "place")
            if done < after or moved:
                return []
            truth = State({("pos", cup): at for cup, at in home.truth().items()})
            happened = person(after, truth)
            for _, cup, position in happened:
                home.simulated.simulation.object_location[f"{cup} cup"] = PLACEMENTS[position]
                home.simulated.simulation.events.record(
                    "sim.disturbance", what="object_moved_by_person", object=f"{cup} cup",
                    to=PLACEMENTS[position])
            seen.extend(happened)
            return [] if unseen else happened

        home = home_cups(START, args.seed, build, noticing=noticing)
        executor = home.executor
        outcome = Interpreter(theory, executor, seed=args.seed).run(do("sort_cups", *GOAL, 4))
        final = home.truth()
        figures = {"skills": home.executor.steps,
                   "sim_time": round(home.simulated.robot.now(), 2)}
    else:
        simulated = SimulatedExecutor(theory, seed=args.seed, events=person,
                                      observed=not unseen)
        executor = simulated
        outcome = Interpreter(theory, executor, seed=args.seed).run(do("sort_cups", *GOAL, 4))
        final = {cup: simulated.truth.get(("pos", cup)) for cup in CUPS}
    replans = [entry for entry in outcome.detail.log if entry["kind"] == "replan"]
    in_order = all(final[cup] == position for cup, position in zip(GOAL, POSITIONS,
                                                                    strict=False))
    if console is not None:
        for entry in outcome.detail.log:
            if entry["kind"] == "plan":
                console.print(f"plan: {', '.join(entry['actions'])}", highlight=False)
            elif entry["kind"] == "action" and entry["ok"]:
                console.print(f"  {entry['action']}", highlight=False)
            elif entry["kind"] == "exogenous":
                console.print(f"  (a person: {entry['action']})", highlight=False)
            elif entry["kind"] == "replan" and entry["marker"].startswith("done("):
                console.print(f"  {entry['marker'][5:-1]} failed ({entry['message']}): "
                              f"re-planning", highlight=False)
            elif entry["kind"] == "replan":
                console.print(f"  marker {entry['marker']} is no longer "
                              f"{str(entry['expected']).lower()}: re-planning",
                              highlight=False)
        console.print("the cups are in order" if in_order else "the cups are not in order")
    noticed = bool(replans) or not moved
    history = outcome.detail.history
    return scenario_summary("cup_moved", outcome.success and in_order and noticed,
                            outcome.detail.actions, [],
                            exogenous=[" ".join(map(str, m)) for m in moved],
                            replans=len(replans), markers=[entry["marker"] for entry in replans],
                            moves_after_disturbance=len(history) - after if moved
                            else None,
                            fewest_after_disturbance=_fewest_after(moved, after, history),
                            **figures)


def _fewest_after(moved: list[tuple[Any, ...]], after: int,
                  history: list[tuple[Any, ...]]) -> int | None:
    if not moved:
        return None
    positions = dict(START)
    for action in history[:after]:
        positions[action[1]] = action[3]
    positions[moved[0][1]] = moved[0][2]
    return minimum_moves(positions, GOAL)
