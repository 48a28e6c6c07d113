"""Order Cups from speech and pointing (CAESAR Fig. 6): "put the red cup there", pointed at.

The four positions p1…p4 lie in a row on the apartment's kitchen table, p1 leftmost
as the person sees it from the table's front. The person wants ``--goal`` (the
cups for p1, p2, p3) and, for each cup in a seeded order, says "put the <colour> cup
there" while pointing at its position: a scripted gesture stands in for the
perception's (shoulder and hand, the hand aimed at the position with ``--spread``
metres of seeded error). The robot reads the request (``deictic_request``), follows
the ray from shoulder through hand to the table top and takes the position closest
to it by the fuzzy closeness of the table's frame (``pointed_place``); when two
positions are about as close, or the position is already given to another cup or is
p4 (which stays free), it asks, and the person points again. The goal order
so understood goes to the Order Cups program (``order_cups_demo``, Alg. 3), whose
``solve`` re-orders the cups in the simulated world. Success: the understood goal is
the person's, the cups end in that order by the simulator's truth, and with the
fewest moves possible (breadth-first search).
"""

from __future__ import annotations

import argparse
import math
import random
from typing import Any

from rich.console import Console

from homebot.geometry import Ray
from homebot.golog import Interpreter, SimulatedExecutor, State
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.scenarios.library.order_cups import goal_order
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.space.deixis import deictic_request, pointed_place
from homebot.space.frames import frames_of
from homebot.world import World, object_positions

__all__ = ["SHARED_OPTIONS", "TABLE", "add_arguments", "position_points", "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.PROBABILITY, "--spread", 0.04,
                               "how far off a pointing gesture aims (standard deviation, "
                               "metres)"),)

TABLE = "kitchen table"
TABLE_HEIGHT = 0.75  #: metres: the table top's plane
SHOULDER = 1.4  #: metres: the person's shoulder height
_LATERAL = (0.45, 0.15, -0.15, -0.45)  #: p1…p4 to the person's left of the table's middle
_TRIES = 3  #: points per cup before the robot gives up


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--goal", default="red,green,blue",
                        help="the cups the person wants at p1, p2, p3, comma separated")
    parser.add_argument("--horizon", type=int, default=4, help="horizon of solve")


def position_points(world: World) -> tuple[dict[str, tuple[float, float]], tuple[float, float],
                                           float]:
    """p1…p4 on the kitchen table (map frame), where the person stands, the table's scale."""
    frame = frames_of(world, object_positions(world, 0))[TABLE]
    depth = world.placements[TABLE].model.size[1] if abs(math.sin(frame.front)) > 0.5 else (
        world.placements[TABLE].model.size[0])
    # the person faces the table from its front: their left is the frame's -y
    points = {name: frame.to_map((0.0, -lateral)) for name, lateral in zip(
        POSITIONS, _LATERAL, strict=True)}
    return points, frame.to_map((depth / 2 + 0.45, 0.0)), frame.scale


def _gesture(rng: random.Random, person: tuple[float, float], target: tuple[float, float],
             spread: float) -> Ray:
    aim = (target[0] + rng.gauss(0.0, spread), target[1] + rng.gauss(0.0, spread), TABLE_HEIGHT)
    shoulder = (person[0], person[1], SHOULDER)
    ray = tuple(a - s for a, s in zip(aim, shoulder, strict=True))
    length = math.sqrt(sum(component * component for component in ray))
    hand = tuple(s + 0.6 * component / length for s, component in zip(shoulder, ray,
                                                                          strict=True))
    return Ray(shoulder, (hand[0], hand[1], hand[2]))


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Understand the goal from speech and pointing, then re-order the cups with solve."""
    wanted = goal_order(getattr(args, "goal", "red,green,blue"))
    spread = getattr(args, "spread", 0.04)
    rng = random.Random(args.seed)
    initial = dict(zip(CUPS, rng.sample(POSITIONS, len(CUPS)), strict=True))
    world = World.load("apartment")
    points, person, scale = position_points(world)
    understood: dict[str, str] = {}
    dialogue: list[str] = []
    asked = 0
    for cup in rng.sample(CUPS, len(CUPS)):
        target = points[POSITIONS[wanted.index(cup)]]
        said = f"put the {cup} cup there"
        for _ in range(_TRIES):
            dialogue.append(f"person: {said} (pointing)")
            what = deictic_request(said)
            place, _ = pointed_place(_gesture(rng, person, target, spread), points,
                                     TABLE_HEIGHT, scale)
            taken = place in understood.values() or place == POSITIONS[-1]
            if what is not None and place is not None and not taken:
                understood[what.removesuffix(" cup")] = place
                dialogue.append(f"robot: the {what} goes to {place}.")
                break
            asked += 1
            dialogue.append("robot: " + ("That place is taken or stays free. " if taken else
                                         "I am not sure where you point. ")
                            + "Please point again.")
    by_position = {place: cup for cup, place in understood.items()}
    goal = tuple(by_position.get(position, "?") for position in POSITIONS[:3])
    right_goal = goal == wanted
    moves: list[tuple[Any, ...]] = []
    in_order, fewest, outcome = False, minimum_moves(initial, wanted), None
    if sorted(goal) == sorted(CUPS):
        theory = cups_theory()
        executor = SimulatedExecutor(theory, seed=args.seed, truth=State(
            {("pos", cup): at for cup, at in initial.items()}))
        outcome = Interpreter(theory, executor, seed=args.seed).run(
            do("order_cups_demo", *goal, getattr(args, "horizon", 4)), State())
        moves = [action for action in outcome.detail.history if action[0] == "move_cup"]
        in_order = all(executor.truth.get(("pos", cup)) == position
                       for cup, position in zip(wanted, POSITIONS, strict=False))
    success = bool(outcome and outcome.success) and right_goal and in_order and (
        len(moves) == fewest)
    if console is not None:
        for line in dialogue:
            console.print(f"  {line}", highlight=False)
        console.print(f"cups at {initial}; understood at p1, p2, p3: {', '.join(goal)} "
                      f"({'as meant' if right_goal else 'not as meant: ' + ', '.join(wanted)})")
        console.print(f"{len(moves)} move{'' if len(moves) == 1 else 's'} (fewest possible: "
                      f"{fewest}); {'in order' if in_order else 'not in order'}")
    speech = [line.removeprefix("robot: ") for line in dialogue if line.startswith("robot: ")]
    return scenario_summary("order_cups_pointing", success,
                            outcome.detail.actions if outcome else [], speech, initial=initial,
                            goal=list(wanted), understood=list(goal), asked_again=asked,
                            moves=len(moves), fewest_moves=fewest)
