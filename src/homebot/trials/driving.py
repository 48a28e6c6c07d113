"""Driving trials: seeded goals through the apartment, driven and judged by the truth.

``drive_goals`` draws the goals (half placement approach poses, half random free points);
``drive`` drives the embodied robot (``SimBody``, people walking) to each in turn with the
robot's whole navigation and one local controller, and judges every goal by the
simulator's truth: reached when the true position ends within 0.3 m, collisions as the
simulation counts them. A missed goal's restart, the situations kept as snapshots and the
per-goal trace are part of the trial, so one goal can be measured alone in the situation
the whole run left it in. ``homebot bench navigation --goals N`` prints the figures.
"""

from __future__ import annotations

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
from scipy import ndimage

from homebot.errors import BenchmarkError, NavigationError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigate import OdometryPose
from homebot.navigation.recovery import RecoveringNavigation, RecoveryPolicy
from homebot.progress import track
from homebot.robot import DriveKind, LaserScan, Twist, VelocityLimits
from homebot.sim.body import SimBody
from homebot.sim.simulation import Simulation
from homebot.world import PlacementKind, World

__all__ = ["DriveOutcome", "DrivingTrial", "Situation", "drive", "drive_goals"]

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


@dataclass(frozen=True)
class DrivingTrial:
    """How the goals are driven: ``homebot bench navigation``'s options of the same names."""

    seed: int = 1  #: seeds goals, people and sensors
    goals: int = 0  #: goals drawn
    walkers: int = 3  #: people walking about
    pose: str = "truth"  #: what the controllers steer by: truth, odometry or mcl
    first: int = 0  #: the first measured goal (the ones before are driven unmeasured)
    only_goal: int | None = None  #: measure this one goal alone
    snapshots: Path | None = None  #: a folder keeping each goal's starting situation
    trace: Path | None = None  #: a JSON-lines file of what happened in each measured goal


def _median_ms(samples: list[float]) -> float:
    return round(1000 * statistics.median(samples), 3)


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


def drive_goals(world: World, navigator: Navigator, count: int, rng: random.Random) -> list[Pose]:
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


@dataclass
class DriveOutcome:
    """What one controller's drives came to, goal by goal, judged by the truth."""

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
    #: each goal's true path: (x, y) at every control period (for ``--plot``)
    paths: list[list[tuple[float, float]]] = field(default_factory=list)

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


def drive(name: str, world: World, navigator: Navigator, targets: list[Pose],
           trial: DrivingTrial) -> DriveOutcome:
    """Drive to every target in turn with one controller; everything judged by the truth.

    Only the goals from ``--from`` (or the one of ``--only-goal``) are measured; the
    ones before are driven unmeasured to reach the measured ones' situation, or that
    situation is read from ``--snapshots``.
    """
    began = time.perf_counter()
    first, last = _span(trial, len(targets))
    situation = _load_situation(trial, name, first, world, navigator)
    if situation is None:
        sim = Simulation(world, seed=trial.seed, navigator=navigator)
        situation = Situation(sim, SimBody(sim, walkers=trial.walkers), _PLANNERS[name](),
                               None, 0)
    sim, body, previous = situation.sim, situation.body, situation.previous
    controller = _Timed(situation.controller)
    outcome, unmeasured = DriveOutcome(), DriveOutcome()
    trace = _Trace(trial.trace, name) if trial.trace is not None else None
    velocities: list[tuple[float, Twist]] = []
    for index in track(range(situation.goal, last), f"driving to goals, {name}"):
        target = targets[index]
        if trial.snapshots is not None:
            _save_situation(trial, name, world, navigator,
                            Situation(sim, body, controller.controller, previous, index))
        measured = outcome if index >= first else unmeasured
        # The last goal was missed: start where it should have, once nobody stands there
        # (carrying the robot onto someone's feet is no collision of its own; with someone
        # standing there for good, it goes on from where it stopped).
        if previous is not None and math.dist(sim.robot_pose[:2], previous.xy()) > _REACHED \
                and _wait_until_clear(body, previous):
            body.teleport(previous)
        truth = Pose(*sim.robot_pose)
        velocities.clear()
        path = [truth.xy()]
        measured.paths.append(path)
        source = _pose_source(trial.pose, sim, body, navigator, truth, trial.seed, index)
        recording = trace is not None and index >= first
        if recording:
            assert trace is not None
            trace.begin(index, target, sim, body)

        def localise(source: Callable[[], Pose] = source, recording: bool = recording,
                     path: list[tuple[float, float]] = path) -> Pose:
            # Once per control period: the navigation may ask again within one.
            if not velocities or velocities[-1][0] < body.now():
                velocities.append((body.now(), body.odometry().twist))
                path.append((sim.robot_pose[0], sim.robot_pose[1]))
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
        if trial.pose == "mcl":
            measured.pose_errors.append(math.dist(source().xy(), sim.robot_pose[:2]))
        if recording:
            assert trace is not None
            trace.end(sim, reached, reason, attempt.duration, sim.collisions[collisions:])
    outcome.first_goal = first
    outcome.cycles = controller.seconds
    outcome.wall_seconds = time.perf_counter() - began
    return outcome


def _span(trial: DrivingTrial, goals: int) -> tuple[int, int]:
    """The measured goals, ``range(first, last)``, from ``--from`` and ``--only-goal``."""
    only = trial.only_goal
    first = only if only is not None else trial.first
    if first >= goals:
        option = "--only-goal" if only is not None else "--from"
        raise BenchmarkError(f"{option} {first}: there are only {goals} goals (0 to "
                             f"{goals - 1}); give a smaller one or more --goals")
    return first, first + 1 if only is not None else goals


@dataclass
class Situation:
    """Everything a goal starts from: the simulation, the body, the controller, the
    goal before (where a missed one restarts the robot) and the goal's index."""

    sim: Simulation
    body: SimBody
    controller: LocalController
    previous: Pose | None
    goal: int


def _snapshot_path(trial: DrivingTrial, name: str, goal: int) -> Path:
    assert trial.snapshots is not None
    return Path(trial.snapshots) / f"goal-{goal:04d}-{name}.pickle.gz"


def _snapshot_key(trial: DrivingTrial, name: str) -> tuple[object, ...]:
    return (name, trial.seed, trial.walkers, trial.pose, trial.goals)


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


def _save_situation(trial: DrivingTrial, name: str, world: World, navigator: Navigator,
                    situation: Situation) -> None:
    path = _snapshot_path(trial, name, situation.goal)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with gzip.open(path, "wb", compresslevel=1) as handle:
            pickler = _Pickler(handle, {id(world): "world", id(navigator): "navigator"})
            pickler.dump((_snapshot_key(trial, name), situation))
    except OSError as error:
        raise BenchmarkError(f"--snapshots {trial.snapshots}: cannot write {path.name} "
                             f"({error.strerror or error}); give a folder you can write") \
            from None


def _load_situation(trial: DrivingTrial, name: str, goal: int, world: World,
                    navigator: Navigator) -> Situation | None:
    """The situation at ``goal``'s start kept in ``--snapshots``, or None (drive there)."""
    if goal == 0 or trial.snapshots is None:
        return None
    path = _snapshot_path(trial, name, goal)
    if not path.is_file():
        return None
    with gzip.open(path, "rb") as handle:
        try:
            key, situation = _Unpickler(handle, {"world": world, "navigator": navigator}).load()
        except (pickle.UnpicklingError, EOFError, OSError, AttributeError, ImportError, TypeError):
            raise BenchmarkError(f"--snapshots: {path} was kept by other code; delete it or "
                                 "give an empty folder") from None
    if key != _snapshot_key(trial, name):
        raise BenchmarkError(f"--snapshots: {path} was kept with other options "
                             f"(planner, seed, walkers, pose, goals: {key}); give the same "
                             "options or an empty folder")
    assert isinstance(situation, Situation)
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

    def __init__(self, *trial: Any, trace: _Trace, **kwargs: Any) -> None:
        super().__init__(*trial, **kwargs)
        self.trace = trace

    def plan_wide(self, here: Pose, target: Pose, avoid_doors: frozenset[str],
                  obstacles: np.ndarray, squeeze: bool = False,
                  extended: np.ndarray | None = None,
                  ) -> tuple[tuple[float, float], ...] | None:
        path = super().plan_wide(here, target, avoid_doors, obstacles, squeeze, extended)
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
