"""Fetch & Carry (CAESAR Alg. 1): a Golog program approaches until "close", fetches, delivers.

Each seed picks an object on a piece of furniture of the apartment and another piece
of furniture to carry it to; objects stand where the world file and the seed put
them (``homebot.world.object_positions``), which is also the robot's items database
Φ. ``fetch_and_carry(obj, dest)`` from ``fetch_carry.golog`` picks the object's
position from Φ, approaches it until the qualitative distance is ``close`` (read in
the frame of the room both points are in, or the world's), picks it up, approaches
the destination the same way and puts it down. The actions run as the monitored
skills (navigate to a point, pick, place). Success is the simulator's truth: the
object lies on the destination, and the robot stood "close" to each point it
approached.
"""

from __future__ import annotations

import argparse
import math
import random
from typing import Any

from rich.console import Console

from homebot.errors import WorldError
from homebot.golog import Interpreter
from homebot.golog.build import do
from homebot.golog.domains.fetch_carry import fetch_carry_theory
from homebot.golog.skill_executor import SkillExecutor
from homebot.golog.theory import GroundAction
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.space.distance import distance_category
from homebot.space.frames import frames_of
from homebot.task import Step
from homebot.world import Placement, PlacementKind, World, front_heading, object_positions

__all__ = ["SHARED_OPTIONS", "add_arguments", "run", "standpoints_in"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),)

Point = tuple[float, float]
_RINGS = tuple(round(0.3 + 0.1 * step, 2) for step in range(14))  #: 0.3 … 1.6 m
_ANGLES = 16
_INSET = 0.15  #: metres from a placement's front edge to where things are put on it


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--object", help="the object to fetch (default: chosen by the seed)")
    parser.add_argument("--to", dest="destination",
                        help="the placement to carry it to (default: chosen by the seed)")


def standpoints_in(world: World) -> Any:
    """``standpoints(p)``: free floor points round p in p's room (the robot fits there),
    on rings 0.3–1.6 m out, nearest first; remembered per point."""
    found: dict[Point, tuple[Point, ...]] = {}

    def standpoints(point: Point) -> tuple[Point, ...]:
        if point not in found:
            room = world.room_at(*point)
            points = []
            for radius in _RINGS:
                for step in range(_ANGLES):
                    angle = 2 * math.pi * step / _ANGLES
                    q = (round(point[0] + radius * math.cos(angle), 3),
                         round(point[1] + radius * math.sin(angle), 3))
                    if world.room_at(*q) == room and world.footprint_problem(*q) is None:
                        points.append(q)
            found[point] = tuple(points)
        return found[point]

    return standpoints


def _choose(world: World, rng: random.Random, args: argparse.Namespace) -> tuple[str, str]:
    furniture = [name for name, p in world.placements.items()
                 if p.model.kind is PlacementKind.FURNITURE]
    objects = sorted(name for name, obj in world.objects.items() if obj.placement in furniture)
    obj = getattr(args, "object", None) or rng.choice(objects)
    if obj not in objects:
        raise WorldError(f"--object '{obj}': not an object on the apartment's furniture; "
                         f"choose one of {', '.join(objects)}")
    destination = getattr(args, "destination", None) or rng.choice(
        [name for name in furniture if name != world.objects[obj].placement])
    world.placement(destination)  # an unknown name: WorldError with a suggestion
    return obj, destination


def _spot(placement: Placement) -> Point:
    """Where things are put on a placement: on its front side, ``_INSET`` in from the edge
    (the middle of a bed is out of reach from its side)."""
    heading = front_heading(placement)
    width, depth = placement.model.size
    half = abs(math.cos(heading)) * width / 2 + abs(math.sin(heading)) * depth / 2
    inset = max(half - _INSET, 0.0)
    cx, cy = placement.model.center
    return (round(cx + inset * math.cos(heading), 3), round(cy + inset * math.sin(heading), 3))


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Fetch a seeded object and carry it to a seeded placement with ``fetch_and_carry``."""
    world = World.load("apartment")
    rng = random.Random(args.seed)
    obj, destination = _choose(world, rng, args)
    positions = object_positions(world, args.seed)
    frames = frames_of(world, positions)

    def frame(a: Point, b: Point) -> tuple[float, float]:
        room_a, room_b = world.room_at(*a), world.room_at(*b)
        name = room_a if room_a is not None and room_a == room_b else "world"
        return frames[name].scale, frames[name].front

    spots = {name: _spot(placement) for name, placement in world.placements.items()}
    simulated = build(world, seed=args.seed)
    context = simulated.context
    start = context.robot.pose().xy()
    theory = fetch_carry_theory(positions, (start[0], start[1]), spots, standpoints_in(world),
                                frame)
    approached: list[dict[str, Any]] = []  #: each goto with where the robot truly stood

    def goto(action: GroundAction) -> list[Step]:
        return [Step("navigate", {"to": [float(action[1][0]), float(action[1][1])]})]

    def sensing(action: GroundAction, done: bool) -> dict[tuple[Any, ...], Any]:
        if action[0] == "goto":
            stood = simulated.simulation.robot_pose[:2]
            approached.append({"to": list(action[1]), "done": done,
                               "stood": [round(stood[0], 3), round(stood[1], 3)]})
        here = context.robot.pose().xy()
        return {("robot",): (round(here[0], 3), round(here[1], 3))}

    bindings = {
        "goto": goto,
        "pickup": lambda action: [Step("pick", {"object": str(action[1])})],
        "putdown": lambda action: [Step("place", {"placement": str(action[2]),
                                                  "object": str(action[1])})],
    }
    executor = SkillExecutor(simulated.executive, bindings, sensing=sensing)
    outcome = Interpreter(theory, executor, seed=args.seed).run(
        do("fetch_and_carry", obj, destination))
    truth = simulated.simulation
    # judged by the truth: how far from each approached point the robot really stood
    for record, target in zip(approached, [positions[obj], spots[destination]], strict=False):
        stood = (record["stood"][0], record["stood"][1])
        scale, _ = frame(target, stood)
        record.update(metres=round(math.dist(stood, target), 2),
                      category=distance_category(math.dist(stood, target), scale))
    delivered = truth.object_location.get(obj) == destination
    close = len(approached) == 2 and all(record["done"] and record["category"] == "close"
                                         for record in approached)
    success = outcome.success and delivered and close
    if console is not None:
        console.print(f"fetch_and_carry({obj}, {destination}): the {obj} is at "
                      f"({positions[obj][0]:.2f}, {positions[obj][1]:.2f}) "
                      f"on the {world.objects[obj].placement}")
        for entry in outcome.detail.log:
            if entry["kind"] == "action":
                console.print(f"  {entry['action']}", highlight=False)
        for record in approached:
            console.print(f"  approached {record['to']}: stood {record['metres']} m away, "
                          f"{record['category']}", highlight=False)
        console.print(f"{'delivered' if delivered else 'not delivered'}: the {obj} is on "
                      f"the {truth.object_location.get(obj)}"
                      f"{'; ' + outcome.reason if outcome.reason else ''}")
    return scenario_summary("fetch_carry", success, executor.steps, [],
                            object=obj, destination=destination, delivered=delivered,
                            approached=approached, golog_actions=outcome.detail.actions,
                            reason=outcome.reason, sim_time=round(context.robot.now(), 2))
