"""Order Cups from speech and pointing (CAESAR Fig. 6): "put the red cup there", pointed at.

The four positions p1…p4 lie in a row on the apartment's kitchen table, p1 leftmost
as the person sees it from the table's front. The person wants ``--goal`` (the
cups for p1, p2, p3) and, for each cup in a seeded order, says "put the <colour> cup
there" while pointing at its position (aimed at it with ``--spread`` metres of
seeded error). The simulator draws the person, their pointing arm included, into the
head camera's RGB-D frames of a robot watching from beside the table
(``sim.body_tracker``); the robot segments head, shoulder and hand from a second of
depth frames (``perception.body_parts``), checks that it is a pointing gesture, and
follows the ray from the eyes through the hand to the table top (``pointing_ray``).
It reads the request (``deictic_request``) and takes the position closest to where the
ray meets the top by the fuzzy closeness of the table's frame (``pointed_place``); when two
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

import numpy as np
import shapely
from rich.console import Console

from homebot.geometry import Pose, Ray
from homebot.golog import Interpreter, SimulatedExecutor, State
from homebot.golog.build import do
from homebot.golog.domains import CUPS, POSITIONS, cups_theory, minimum_moves
from homebot.perception.body_parts import arm_track, looking_tilt
from homebot.perception.gestures import person_gesture, pointing_ray
from homebot.robot import HeadState
from homebot.scenarios.library.order_cups import goal_order
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import scenario_summary
from homebot.sim.body_tracker import PeopleArms, person_solids
from homebot.sim.camera import CameraSimulator, SceneGeometry
from homebot.sim.keypoints import draw_motion
from homebot.space.deixis import deictic_request, pointed_place
from homebot.space.frames import frames_of
from homebot.world import PersonModel, Posture, World, object_positions

__all__ = ["SHARED_OPTIONS", "TABLE", "add_arguments", "position_points", "run",
           "watching_pose"]

SHARED_OPTIONS = (SharedOption(OptionKind.PROBABILITY, "--spread", 0.04,
                               "how far off a pointing gesture aims (standard deviation, "
                               "metres)"),)

TABLE = "kitchen table"
TABLE_HEIGHT = 0.75  #: metres: the table top's plane
_LATERAL = (0.45, 0.15, -0.15, -0.45)  #: p1…p4 to the person's left of the table's middle
_TRIES = 3  #: points per cup before the robot gives up
_WATCHING = 1.5  #: metres beside the person (along the table's front) the robot watches from
_FRAMES, _EVERY = 10, 0.1  #: the head camera's burst: frames, seconds between them
_PERSON = "Pat"


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


def watching_pose(world: World, person: tuple[float, float]) -> Pose:
    """Where the robot stands to watch the person point: beside them along the table's
    front, on the side with the more room, facing them."""
    frame = frames_of(world, object_positions(world, 0))[TABLE]
    depth = world.placements[TABLE].model.size[1] if abs(math.sin(frame.front)) > 0.5 else (
        world.placements[TABLE].model.size[0])
    room = world.room_at(*person)
    for side in (1.0, -1.0):
        x, y = frame.to_map((depth / 2 + 0.45, side * _WATCHING))
        if world.room_at(x, y) == room and not any(
                p.footprint.distance(shapely.Point(x, y)) < 0.3 for p in world.placements.values()):
            return Pose(x, y, math.atan2(person[1] - y, person[0] - x))
    raise ValueError(f"no room beside the {TABLE} to watch from")


class _PointingPerson:
    """The person at the table, drawn by the simulator pointing at a spot, and the robot's
    head camera watching them: the ray the robot reads from its depth frames."""

    def __init__(self, world: World, person: tuple[float, float], seed: int) -> None:
        self.world = world
        self.person = person
        self.rng = np.random.default_rng([seed, 31])
        self.camera = CameraSimulator(SceneGeometry.of(world), np.random.default_rng([seed, 37]))
        self.robot = watching_pose(world, person)
        self.model = PersonModel(name=_PERSON, room=world.room_at(*person) or "",
                                 position=person, clothes=["green sweater", "blue jeans"])
        self.now = 0.0

    def point_at(self, aim: tuple[float, float, float]) -> Ray | None:
        """The ray from the eyes through the hand the robot sees the person point along at
        ``aim``; None when it sees no pointing."""
        robot, person = self.robot, self.person
        facing = math.atan2(robot.y - person[1], robot.x - person[0])
        their_right = (math.sin(facing), -math.cos(facing))
        side = "right" if (aim[0] - person[0]) * their_right[0] + (
            aim[1] - person[1]) * their_right[1] > 0 else "left"
        arms = PeopleArms(0)
        arms.gestures[_PERSON] = draw_motion("pointing", self.rng, target=aim, side=side,
                                             aim=0.0)
        body = person_solids(self.world, _PERSON, self.model, Posture.STANDING, person, facing)
        head = HeadState(0.0, looking_tilt(math.dist(person, robot.xy()),
                                           self.camera.intrinsics))
        frames = []
        for _ in range(_FRAMES):
            self.now += _EVERY
            solids = [*body, *arms.solids(_PERSON, self.model, Posture.STANDING, person,
                                          robot.xy(), self.now)]
            frames.append(self.camera.render(self.now, (robot.x, robot.y, robot.theta), head,
                                             solids))
        track = arm_track(frames, [robot] * len(frames), person)
        if track is None or not person_gesture(track, robot.xy()).startswith("pointing"):
            return None
        return pointing_ray(track)


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Understand the goal from speech and pointing, then re-order the cups with solve."""
    wanted = goal_order(getattr(args, "goal", "red,green,blue"))
    spread = getattr(args, "spread", 0.04)
    rng = random.Random(args.seed)
    initial = dict(zip(CUPS, rng.sample(POSITIONS, len(CUPS)), strict=True))
    world = World.load("apartment")
    points, person, scale = position_points(world)
    pointer = _PointingPerson(world, person, args.seed)
    understood: dict[str, str] = {}
    dialogue: list[str] = []
    asked = 0
    for cup in rng.sample(CUPS, len(CUPS)):
        target = points[POSITIONS[wanted.index(cup)]]
        said = f"put the {cup} cup there"
        for _ in range(_TRIES):
            dialogue.append(f"person: {said} (pointing)")
            what = deictic_request(said)
            ray = pointer.point_at((target[0] + rng.gauss(0.0, spread),
                                    target[1] + rng.gauss(0.0, spread), TABLE_HEIGHT))
            place = None if ray is None else pointed_place(ray, points, TABLE_HEIGHT, scale)[0]
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
