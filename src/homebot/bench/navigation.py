"""Navigation: stage-1 A* timing, and 200 goals driven through the apartment with people walking.

**Timing**: stage-1 A* for 15 m paths on a 5 cm grid (open floor, round a long
wall, and round a long wall on a grid the apartment's size): on a grid whose
jump tables are kept, on a grid seen for the first time, the tables' build
alone, and libtcod alone; and ``Navigator.plan`` between every placement pair.

**Driving** (``--goals N``): the embodied robot (``SimBody``, three people
walking) drives to N seeded goals in turn, half placement approach poses and
half random free points, each with the robot's whole navigation
(``RecoveringNavigation``: stage 1's path, a local controller, and replanning
round what the laser sees or waiting when blocked) with two local controllers:
CAESAR's stage 2 (``MotionSearchPlanner``) and the Dynamic Window Approach
baseline, each in its own simulation with the same seed and goals.
Everything is judged by the simulator's truth: collisions are
``simulation.collisions`` (walls, furniture, people); a goal is reached when
the true position ends within 0.3 m of it. When a goal was missed, the robot
is carried (truth only) to that goal before the next one, so both controllers
always face the same start and goal. Smoothness is the mean absolute angular
acceleration of the base (rad/s², from the velocity at each 20 Hz tick while
driving); also reported: mean absolute linear acceleration. Cycle times are
wall-clock per ``plan`` call on whatever core this runs on (``taskset -c 0``).
The pose the controllers steer by is ``--pose``: the truth (default, fast),
odometry anchored at each goal's start (it drifts during the goal), or Monte
Carlo localisation started near the truth at each goal (as the robot does).

**One goal alone**: ``--only-goal K`` (or ``--from K``) measures goal K (0-based, as
``missed goals`` lists them) in its own situation: the robot, the people and their
seeded schedules as the whole run left them. The goals before are driven unmeasured,
or, with ``--snapshots DIR`` (written by an earlier run with the same options and code),
the situation is read back from there. ``--trace FILE`` writes each measured goal as
a JSON line: the true pose, velocity and people at every control period, and every
stage-1 plan (None: the robot waited).
"""

from __future__ import annotations

import argparse
import gzip
import itertools
import json
import math
import pickle
import random
import statistics
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console
from scipy import ndimage

from homebot.bench.arguments import count, seed
from homebot.errors import BenchmarkError, NavigationError
from homebot.geometry import Pose
from homebot.navigation import Navigator, astar
from homebot.navigation.astar import cached_jump_tables, forget_jump_tables, libtcod_astar
from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.jump_points import jump_tables
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigate import OdometryPose
from homebot.navigation.recovery import RecoveringNavigation, RecoveryPolicy
from homebot.robot import DriveKind, LaserScan, Twist, VelocityLimits
from homebot.sim.body import SimBody
from homebot.sim.simulation import Simulation
from homebot.world import PlacementKind, World

__all__ = ["add_arguments", "run"]

_REACHED = 0.3  #: metres from the goal, by the truth
_TOLERANCE = 0.15  #: metres: the navigation's own goal tolerance (by its pose estimate)
_HEADING_TOLERANCE = 0.2  #: radians
_CLEARING_WAIT = 120.0  #: seconds the bench waits for people to leave a restart spot
_CLEAR_SPOT = 0.4  #: metres beyond the robot's radius a restart spot keeps from legs
_GOAL_CLEARANCE = 0.45  #: a random free goal keeps this far from walls and furniture
# Nobody here asks people to step aside (the executive does that for the robot), so the
# robot waits for the way to clear as long as its budget allows.
_POLICY = RecoveryPolicy(patience=RecoveryPolicy.wait_budget)
_PLANNERS: dict[str, Callable[[], LocalController]] = {
    "stage2": MotionSearchPlanner, "dwa": DynamicWindowPlanner}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeat", type=count("--repeat", 1, 10_000), default=50,
                        help="searches per A* timing case")
    parser.add_argument("--goals", type=count("--goals", 0, 5000), default=0,
                        help="goals to drive to per controller (0: timing only; the issue's "
                             "figure is --goals 200)")
    parser.add_argument("--planner", choices=["stage2", "dwa", "both"], default="both",
                        help="which local controller drives")
    parser.add_argument("--pose", choices=["truth", "odometry", "mcl"], default="truth",
                        help="the pose the controllers steer by (mcl: Monte Carlo "
                             "localisation from the laser, as the robot does)")
    parser.add_argument("--walkers", type=count("--walkers", 0, 20), default=3,
                        help="people walking about")
    parser.add_argument("--seed", type=seed, default=1, help="seeds goals, people and sensors")
    parser.add_argument("--from", dest="first", type=count("--from", 0, 4999), default=0,
                        help="drive from this goal on (0-based, as 'per goal' lists them); the "
                             "goals before it are driven unmeasured to reach its situation "
                             "(robot, people, schedules), or read from --snapshots")
    parser.add_argument("--only-goal", type=count("--only-goal", 0, 4999), default=None,
                        help="drive this one goal alone (0-based), in its situation as --from")
    parser.add_argument("--snapshots", type=Path, default=None,
                        help="a folder: the situation at each goal's start is kept there "
                             "(goal-NNNN-PLANNER.pickle.gz), and read back by --from/--only-goal "
                             "instead of driving the goals before (same code, seed, walkers)")
    parser.add_argument("--trace", type=Path, default=None,
                        help="write what happened in each measured goal (JSON lines: the "
                             "robot's true pose, people, stops, replans) to this file")


def _median_ms(samples: list[float]) -> float:
    return round(1000 * statistics.median(samples), 3)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """A* timing, then (with ``--goals``) the driving comparison."""
    figures = _astar_timing(args.repeat)
    if args.goals:
        figures["driving"] = _driving(args)
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}")
    return {"benchmark": "navigation", "figures": figures}


def _astar_timing(repeat: int) -> dict[str, Any]:
    """Time stage-1 A* on 15 m cases and ``Navigator.plan`` (uncached) in the apartment.

    Per case: ``median_ms`` is ``astar`` on a grid whose jump tables are kept
    (as the Navigator's static masks'): JPS over the kept tables (or in a
    small window round start and goal, when that window is at most 1/32 of the
    grid and proves its path); ``first_search_ms`` on a grid never seen
    (``plan_around``'s new mask each call), whose tables are built first;
    ``tables_ms`` building the whole grid's jump tables alone;
    ``libtcod_ms`` the search by libtcod's A* alone, as stage 1
    ran before jump point search. Each is a median wall-clock time, and beside
    it (``*cpu_ms``) the median CPU time of the thread: on a shared, loaded
    machine the wall clock also counts the time spent waiting for the core.
    """
    side = 400  # 20 m at 5 cm
    free = np.zeros((side, side), dtype=bool)
    free[0, :] = free[-1, :] = free[:, 0] = free[:, -1] = True
    # A wall with a gap forces a detour, as a doorway does.
    obstacle = free.copy()
    obstacle[50:350, 200] = True
    # The apartment's grid size (208 x 248 cells), a wall across all but its ends.
    apartment = np.zeros((208, 248), dtype=bool)
    apartment[0, :] = apartment[-1, :] = apartment[:, 0] = apartment[:, -1] = True
    apartment[10:198, 124] = True
    cases = {
        "open floor, straight 15 m": (free, (50, 50), (50, 350)),
        "open floor, diagonal 15 m": (free, (50, 50), (262, 262)),
        "wall with a gap, 15 m": (obstacle, (200, 50), (200, 350)),
        "long wall, apartment-sized grid, 14 m": (apartment, (104, 20), (104, 228)),
    }
    figures: dict[str, Any] = {}
    for name, (grid, start, goal) in cases.items():
        figures[name] = _astar_case(grid, start, goal, repeat)
    world = World.load("apartment")
    samples = []
    began_grid = time.perf_counter()
    navigator = Navigator(world)
    grid_seconds = time.perf_counter() - began_grid
    pairs = [(a, b) for a in world.placements for b in world.placements if a < b]
    lengths = []
    for a, b in pairs:
        navigator._cache.clear()  # time the search, not the cache
        began = time.perf_counter()
        plan = navigator.plan(world.placements[a].approach.xy(), world.placements[b].approach.xy())
        samples.append(time.perf_counter() - began)
        lengths.append(plan.length if plan else 0.0)
    figures["apartment plan (all placement pairs)"] = {
        "median_ms": _median_ms(samples), "max_ms": round(1000 * max(samples), 3),
        "pairs": len(pairs), "longest_m": round(max(lengths), 2)}
    mask = navigator.grid.blocked_with(frozenset())
    table_samples = []
    for _ in range(repeat):
        began = time.perf_counter()
        jump_tables(mask.ravel(), navigator.grid.shape)
        table_samples.append(time.perf_counter() - began)
    figures["apartment grid rasterisation"] = {"ms": round(1000 * grid_seconds, 1),
                                               "cells": int(np.prod(navigator.grid.shape)),
                                               "jump_tables_ms": _median_ms(table_samples)}
    return figures


def _astar_case(grid: np.ndarray, start: tuple[int, int], goal: tuple[int, int],
                repeat: int) -> dict[str, Any]:
    """One A* timing case: kept tables, a first search, the tables alone, libtcod alone."""
    flat, columns = grid.ravel(), grid.shape[1]
    origin, target = start[0] * columns + start[1], goal[0] * columns + goal[1]
    wall: dict[str, list[float]] = {"": [], "first_search_": [], "tables_": [], "libtcod_": []}
    cpu: dict[str, list[float]] = {name: [] for name in wall}
    lengths = set()

    def clock(name: str, work: Callable[[], Any]) -> Any:
        began, began_cpu = time.perf_counter(), time.thread_time()
        result = work()
        cpu[name].append(time.thread_time() - began_cpu)
        wall[name].append(time.perf_counter() - began)
        return result

    for _ in range(repeat):
        forget_jump_tables()
        path = clock("first_search_", lambda: astar(flat, grid.shape, origin, target))
        clock("tables_", lambda: jump_tables(flat, grid.shape))
        cached_jump_tables(flat, grid.shape)
        kept = clock("", lambda: astar(flat, grid.shape, origin, target))
        reference = clock("libtcod_", lambda: libtcod_astar(flat, grid.shape, origin, target))
        lengths |= {len(found or []) for found in (path, kept, reference)}
    forget_jump_tables()
    figures: dict[str, Any] = {}
    for name in wall:
        figures[f"{name or 'median_'}ms"] = _median_ms(wall[name])
        figures[f"{name}cpu_ms"] = _median_ms(cpu[name])
    figures["cells"] = sorted(lengths)
    return figures


# ---------------------------------------------------------------------- driving


@dataclass
class _Timed:
    """A controller whose ``plan`` calls are timed (wall clock)."""

    controller: LocalController
    seconds: list[float] = field(default_factory=list)

    def plan(self, pose: Pose, velocity: Twist, scan: LaserScan,
             path: Sequence[tuple[float, float]], limits: VelocityLimits, drive: DriveKind,
             radius: float) -> Twist:
        began = time.perf_counter()
        command = self.controller.plan(pose, velocity, scan, path, limits, drive, radius)
        self.seconds.append(time.perf_counter() - began)
        return command


def _goals(world: World, navigator: Navigator, count: int, rng: random.Random) -> list[Pose]:
    """Half placement approach poses, half random free points (kept clear of obstacles)."""
    grid = navigator.grid
    clearance = ndimage.distance_transform_edt(~grid.occupied) * grid.resolution
    spots = sorted(p.name for p in world.placements.values()
                   if p.model.kind is PlacementKind.FURNITURE)
    min_x, min_y, max_x, max_y = world.bounds()
    goals: list[Pose] = []
    while len(goals) < count:
        if len(goals) % 2 == 0:
            goals.append(world.placements[rng.choice(spots)].approach)
            continue
        x, y = rng.uniform(min_x, max_x), rng.uniform(min_y, max_y)
        if world.room_at(x, y) is None or clearance[grid.cell_of(x, y)] < _GOAL_CLEARANCE:
            continue
        goals.append(Pose(x, y, rng.uniform(-math.pi, math.pi)))
    return goals


def _driving(args: argparse.Namespace) -> dict[str, Any]:
    world = World.load("apartment")
    navigator = Navigator(world)
    targets = _goals(world, navigator, args.goals, random.Random(f"goals:{args.seed}"))
    names = ["stage2", "dwa"] if args.planner == "both" else [args.planner]
    outcomes = {name: _drive(name, world, navigator, targets, args) for name in names}
    figures: dict[str, Any] = {
        name: outcome.summary() for name, outcome in outcomes.items()}
    figures["pose source"] = args.pose
    figures["walkers"] = args.walkers
    if len(outcomes) == 2:
        stage2, dwa = outcomes["stage2"], outcomes["dwa"]
        both = [i for i in range(len(stage2.reached)) if stage2.reached[i] and dwa.reached[i]]
        if both:
            time_stage2 = statistics.fmean(stage2.durations[i] for i in both)
            time_dwa = statistics.fmean(dwa.durations[i] for i in both)
            figures["stage2 vs dwa"] = {
                "goals reached by both": len(both),
                "mean time on them, s": [round(time_stage2, 2), round(time_dwa, 2)],
                "time ratio": round(time_stage2 / time_dwa, 3),
                "angular acceleration ratio": round(
                    stage2.summary()["mean |angular acceleration|, rad/s2"] /
                    max(dwa.summary()["mean |angular acceleration|, rad/s2"], 1e-9), 3)}
    return figures


@dataclass
class _Outcome:
    reached: list[bool] = field(default_factory=list)
    durations: list[float] = field(default_factory=list)
    reasons: dict[str, int] = field(default_factory=dict)
    collisions: list[dict[str, object]] = field(default_factory=list)
    angular: list[float] = field(default_factory=list)
    linear: list[float] = field(default_factory=list)
    cycles: list[float] = field(default_factory=list)
    travelled: float = 0.0
    wall_seconds: float = 0.0
    replans: int = 0
    waits: int = 0
    pose_errors: list[float] = field(default_factory=list)
    first_goal: int = 0  #: the index of the first measured goal

    def summary(self) -> dict[str, Any]:
        goals = len(self.reached)
        return {
            "goals": goals,
            "reached (truth, 0.3 m)": sum(self.reached),
            "reached share": round(sum(self.reached) / goals, 4) if goals else 0.0,
            "collisions": len(self.collisions),
            "collided with": sorted({str(c["with"]) for c in self.collisions}),
            "missed goals (0-based)": [self.first_goal + i for i, r in enumerate(self.reached)
                                       if not r],
            "stop reasons": dict(sorted(self.reasons.items())),
            "mean time per goal, s": round(statistics.fmean(self.durations), 2)
            if self.durations else 0.0,
            "mean |angular acceleration|, rad/s2": round(statistics.fmean(self.angular), 4)
            if self.angular else 0.0,
            "mean |linear acceleration|, m/s2": round(statistics.fmean(self.linear), 4)
            if self.linear else 0.0,
            "travelled, m": round(self.travelled, 1),
            "replans round unexpected obstacles": self.replans,
            "waits for the way to clear": self.waits,
            "pose error at goal (mcl), median m": round(statistics.median(self.pose_errors), 3)
            if self.pose_errors else None,
            "cycle median ms": _median_ms(self.cycles) if self.cycles else None,
            "cycle p95 ms": round(1000 * float(np.percentile(self.cycles, 95)), 3)
            if self.cycles else None,
            "wall seconds": round(self.wall_seconds, 1),
            "per goal": {"first": self.first_goal,
                         "reached": [int(r) for r in self.reached],
                         "seconds": [round(d, 2) for d in self.durations]},
        }


def _drive(name: str, world: World, navigator: Navigator, targets: list[Pose],
           args: argparse.Namespace) -> _Outcome:
    """Drive to every target in turn with one controller; everything judged by the truth.

    Only the goals from ``--from`` (or the one of ``--only-goal``) are measured; the
    ones before are driven unmeasured to reach the measured ones' situation, or that
    situation is read from ``--snapshots``.
    """
    began = time.perf_counter()
    first, last = _span(args, len(targets))
    situation = _load_situation(args, name, first, world, navigator)
    if situation is None:
        sim = Simulation(world, seed=args.seed, navigator=navigator)
        situation = _Situation(sim, SimBody(sim, walkers=args.walkers), _PLANNERS[name](),
                               None, 0)
    sim, body, previous = situation.sim, situation.body, situation.previous
    controller = _Timed(situation.controller)
    outcome, unmeasured = _Outcome(), _Outcome()
    trace = _Trace(args.trace, name) if args.trace is not None else None
    velocities: list[tuple[float, Twist]] = []
    for index in range(situation.goal, last):
        target = targets[index]
        if args.snapshots is not None:
            _save_situation(args, name, world, navigator,
                            _Situation(sim, body, controller.controller, previous, index))
        measured = outcome if index >= first else unmeasured
        # The last goal was missed: start where it should have, once nobody stands there
        # (carrying the robot onto someone's feet is no collision of its own; with someone
        # standing there for good, it goes on from where it stopped).
        if previous is not None and math.dist(sim.robot_pose[:2], previous.xy()) > _REACHED \
                and _wait_until_clear(body, previous):
            body.teleport(previous)
        truth = Pose(*sim.robot_pose)
        velocities.clear()
        source = _pose_source(args.pose, sim, body, navigator, truth, args.seed, index)
        recording = trace is not None and index >= first
        if recording:
            assert trace is not None
            trace.begin(index, target, sim, body)

        def localise(source: Callable[[], Pose] = source, recording: bool = recording) -> Pose:
            # Once per control period: the navigation may ask again within one.
            if not velocities or velocities[-1][0] < body.now():
                velocities.append((body.now(), body.odometry().twist))
                if recording:
                    assert trace is not None
                    trace.tick(sim, body)
            return source()

        navigation = RecoveringNavigation(body, navigator, controller, localise, _POLICY) \
            if trace is None or not recording else \
            _TracedNavigation(body, navigator, controller, localise, _POLICY, trace=trace)
        collisions = len(sim.collisions)
        previous = target
        try:
            attempt = navigation.drive(target, tolerance=_TOLERANCE,
                                       heading_tolerance=_HEADING_TOLERANCE)
        except NavigationError:
            measured.reached.append(False)
            measured.durations.append(0.0)
            measured.reasons["no path"] = measured.reasons.get("no path", 0) + 1
            continue
        reached = math.dist(sim.robot_pose[:2], target.xy()) <= _REACHED
        measured.reached.append(reached)
        measured.durations.append(attempt.duration)
        reason = str(attempt.reason) if reached else f"{attempt.reason} (missed)"
        measured.reasons[reason] = measured.reasons.get(reason, 0) + 1
        measured.replans += attempt.replans
        measured.waits += attempt.waits
        measured.collisions.extend(sim.collisions[collisions:])
        measured.travelled += attempt.travelled
        for (_, before), (_, after) in itertools.pairwise(velocities):
            measured.angular.append(abs(after.wz - before.wz) / body.tick_period)
            measured.linear.append(math.hypot(after.vx - before.vx, after.vy - before.vy) /
                                   body.tick_period)
        if args.pose == "mcl":
            measured.pose_errors.append(math.dist(source().xy(), sim.robot_pose[:2]))
        if recording:
            assert trace is not None
            trace.end(sim, reached, reason, attempt.duration, sim.collisions[collisions:])
    outcome.first_goal = first
    outcome.cycles = controller.seconds
    outcome.wall_seconds = time.perf_counter() - began
    return outcome


def _span(args: argparse.Namespace, goals: int) -> tuple[int, int]:
    """The measured goals, ``range(first, last)``, from ``--from`` and ``--only-goal``."""
    only = getattr(args, "only_goal", None)
    first = only if only is not None else getattr(args, "first", 0)
    if first >= goals:
        option = "--only-goal" if only is not None else "--from"
        raise BenchmarkError(f"{option} {first}: there are only {goals} goals (0 to "
                             f"{goals - 1}); give a smaller one or more --goals")
    return first, first + 1 if only is not None else goals


@dataclass
class _Situation:
    """Everything a goal starts from: the simulation, the body, the controller, the
    goal before (where a missed one restarts the robot) and the goal's index."""

    sim: Simulation
    body: SimBody
    controller: LocalController
    previous: Pose | None
    goal: int


def _snapshot_path(args: argparse.Namespace, name: str, goal: int) -> Path:
    assert args.snapshots is not None
    return Path(args.snapshots) / f"goal-{goal:04d}-{name}.pickle.gz"


def _snapshot_key(args: argparse.Namespace, name: str) -> tuple[object, ...]:
    return (name, args.seed, args.walkers, args.pose, args.goals)


class _Pickler(pickle.Pickler):
    """Keeps the world and the navigator out of a snapshot (they are loaded again)."""

    def __init__(self, file: Any, shared: dict[int, str]) -> None:
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self.shared = shared

    def persistent_id(self, obj: Any) -> str | None:
        return self.shared.get(id(obj))


class _Unpickler(pickle.Unpickler):
    def __init__(self, file: Any, shared: dict[str, object]) -> None:
        super().__init__(file)
        self.shared = shared

    def persistent_load(self, pid: Any) -> object:
        return self.shared[str(pid)]


def _save_situation(args: argparse.Namespace, name: str, world: World, navigator: Navigator,
                    situation: _Situation) -> None:
    path = _snapshot_path(args, name, situation.goal)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with gzip.open(path, "wb", compresslevel=1) as handle:
            pickler = _Pickler(handle, {id(world): "world", id(navigator): "navigator"})
            pickler.dump((_snapshot_key(args, name), situation))
    except OSError as error:
        raise BenchmarkError(f"--snapshots {args.snapshots}: cannot write {path.name} "
                             f"({error.strerror or error}); give a folder you can write") \
            from None


def _load_situation(args: argparse.Namespace, name: str, goal: int, world: World,
                    navigator: Navigator) -> _Situation | None:
    """The situation at ``goal``'s start kept in ``--snapshots``, or None (drive there)."""
    if goal == 0 or args.snapshots is None:
        return None
    path = _snapshot_path(args, name, goal)
    if not path.is_file():
        return None
    with gzip.open(path, "rb") as handle:
        try:
            key, situation = _Unpickler(handle, {"world": world, "navigator": navigator}).load()
        except (pickle.UnpicklingError, EOFError, OSError, AttributeError, ImportError, TypeError):
            raise BenchmarkError(f"--snapshots: {path} was kept by other code; delete it or "
                                 "give an empty folder") from None
    if key != _snapshot_key(args, name):
        raise BenchmarkError(f"--snapshots: {path} was kept with other options "
                             f"(planner, seed, walkers, pose, goals: {key}); give the same "
                             "options or an empty folder")
    assert isinstance(situation, _Situation)
    return situation


class _Trace:
    """What happened in each measured goal, as one JSON line per goal."""

    def __init__(self, path: Path, planner: str) -> None:
        self.path, self.planner = path, planner
        self.record: dict[str, Any] = {}
        try:
            path.write_text("")
        except OSError as error:
            raise BenchmarkError(f"--trace {path}: cannot be written "
                                 f"({error.strerror or error}); give a file you can write") \
                from None

    def begin(self, goal: int, target: Pose, sim: Simulation, body: SimBody) -> None:
        self.record = {"planner": self.planner, "goal": goal, "target": _rounded(target),
                       "start": _rounded(Pose(*sim.robot_pose)), "began": round(body.now(), 2),
                       "ticks": [], "plans": []}

    def tick(self, sim: Simulation, body: SimBody) -> None:
        twist = body.odometry().twist
        people = {name: [round(v, 2) for v in state.position]
                  for name, state in sorted(sim.people.items())}
        self.record["ticks"].append({
            "t": round(body.now(), 2), "pose": _rounded(Pose(*sim.robot_pose)),
            "v": [round(twist.vx, 2), round(twist.vy, 2), round(twist.wz, 2)],
            "people": people})

    def planned(self, now: float, here: Pose, obstacles: np.ndarray, squeeze: bool,
                path: tuple[tuple[float, float], ...] | None) -> None:
        """Record a stage-1 path the navigation planned (None: none was found)."""
        self.record["plans"].append({
            "t": round(now, 2), "from": _rounded(here),
            "obstacles": len(obstacles), "squeeze": squeeze,
            "path": None if path is None else [[round(x, 2), round(y, 2)] for x, y in path]})

    def end(self, sim: Simulation, reached: bool, reason: str, duration: float,
            collisions: list[dict[str, object]]) -> None:
        self.record.update(reached=reached, reason=reason, duration=round(duration, 2),
                           end=_rounded(Pose(*sim.robot_pose)),
                           collisions=[str(c.get("with")) for c in collisions])
        with self.path.open("a") as handle:
            handle.write(json.dumps(self.record) + "\n")


class _TracedNavigation(RecoveringNavigation):
    """The navigation, telling ``trace`` every stage-1 path it plans."""

    def __init__(self, *args: Any, trace: _Trace, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.trace = trace

    def plan_wide(self, here: Pose, target: Pose, avoid_doors: frozenset[str],
                  obstacles: np.ndarray, squeeze: bool = False,
                  ) -> tuple[tuple[float, float], ...] | None:
        path = super().plan_wide(here, target, avoid_doors, obstacles, squeeze)
        self.trace.planned(self.body.now(), here, obstacles, squeeze, path)
        return path


def _rounded(pose: Pose) -> list[float]:
    return [round(pose.x, 3), round(pose.y, 3), round(pose.theta, 3)]


def _wait_until_clear(body: SimBody, spot: Pose) -> bool:
    """Let the people walk on (the robot standing still) until none stands at ``spot``;
    False if someone still does after a while."""
    body.command_velocity(Twist())
    for _ in range(int(_CLEARING_WAIT / body.tick_period)):
        if all(math.dist(leg, spot.xy()) > body.radius + _CLEAR_SPOT
               for leg in body.people.legs()):
            return True
        body.tick()
    return False


def _pose_source(kind: str, sim: Simulation, body: SimBody, navigator: Navigator, truth: Pose,
                 seed: int, goal: int) -> Callable[[], Pose]:
    """What the robot steers by: the truth, odometry anchored at the goal's start, or MCL
    (started near the truth at each goal, as a robot that knew where it was)."""
    if kind == "truth":
        return lambda: Pose(*sim.robot_pose)
    if kind == "odometry":
        return OdometryPose(body, truth)
    localisation = MonteCarloLocalisation(
        navigator.grid, np.random.default_rng([seed, goal, 7]),
        MclParameters(odom_model_type=body.drive))
    localisation.initialise(truth, spread=0.05, angle_spread=0.05)
    return lambda: localisation.update(body.odometry(), body.scan())
