"""The sealed robot: the embodied robot knows only what its Body port tells it.

Three checks: the robot's packages import nothing of the simulator (in a fresh
interpreter, so nothing else has imported it first); a ``BodyRobot`` drives through a
home over a scripted body that has no simulation behind it (its laser is cast on an
occupancy grid here, in the test); and the embodied run's robot reaches nothing of the
simulation but through its ``SimBody``.
"""

from __future__ import annotations

import gc
import math
import subprocess
import sys
import types
from collections.abc import Iterator

import numpy as np
import pytest

from homebot.errors import PartMissing
from homebot.events import EventLog
from homebot.geometry import Pose, wrap_angle
from homebot.navigation import Navigator
from homebot.robot import (
    Body,
    DriveKind,
    HeadState,
    LaserScan,
    Odometry,
    Speaker,
    Twist,
    VelocityLimits,
)
from homebot.world import OccupancyGrid, World

_ROBOT_PACKAGES = ("homebot.embodied", "homebot.navigation", "homebot.perception",
                   "homebot.manipulation", "homebot.speech")


def test_the_robots_packages_import_nothing_of_the_simulator() -> None:
    """Imported in a fresh interpreter, every module of the robot's packages leaves
    ``homebot.sim`` unloaded: not even a module they import imports it."""
    script = f"""
import importlib, pkgutil, sys
for package in {_ROBOT_PACKAGES!r}:
    module = importlib.import_module(package)
    for info in pkgutil.walk_packages(module.__path__, package + "."):
        try:
            importlib.import_module(info.name)
        except ImportError as missing:  # an optional extra this machine lacks
            print("skipped", info.name, missing, file=sys.stderr)
print(sorted(name for name in sys.modules if name.startswith("homebot.sim")))
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          check=True)
    assert done.stdout.strip() == "[]", done.stdout


class _ScriptedSpeaker(Speaker):
    def __init__(self) -> None:
        self.rate = 16_000
        self.said: list[str] = []

    def play(self, samples: np.ndarray, *, text: str | None = None) -> float:
        self.said.append(text or "")
        return samples.size / self.rate


class ScriptedBody(Body):
    """A body with nothing behind it but a map: it moves where it is told, perfectly,
    and its laser is cast on the occupancy grid it was given. No simulation, no truth
    of objects, people or doors: the grid's doors are all open."""

    def __init__(self, grid: OccupancyGrid, start: Pose) -> None:
        self.drive = DriveKind.DIFFERENTIAL
        self.limits = VelocityLimits()
        self.radius = 0.25
        self.tick_period = 0.05
        self.grid = grid
        self.pose = start
        self._time = 0.0
        self._command = Twist()
        self._head = HeadState()
        self._stopped = False
        self.speaker_part = _ScriptedSpeaker()

    def now(self) -> float:
        return self._time

    def tick(self, ticks: int = 1) -> None:
        for _ in range(ticks):
            twist = Twist() if self._stopped else self._command
            dt = self.tick_period
            theta = self.pose.theta + twist.wz * dt / 2
            moved = Pose(self.pose.x + twist.vx * dt * math.cos(theta),
                         self.pose.y + twist.vx * dt * math.sin(theta),
                         wrap_angle(self.pose.theta + twist.wz * dt))
            row, column = self.grid.cell_of(moved.x, moved.y)
            if not self.grid.occupied[row, column]:  # a bumper: no driving into walls
                self.pose = moved
            self._time += dt

    def command_velocity(self, twist: Twist) -> None:
        self._command = self.limits.clip(twist, self.drive)

    def odometry(self) -> Odometry:
        return Odometry(self._time, self.pose, self._command)

    def scan(self) -> LaserScan:
        beams, field = 271, 4.712389
        angles = self.pose.theta - field / 2 + field / (beams - 1) * np.arange(beams)
        steps = np.arange(0.05, 10.0, self.grid.resolution / 2)
        xs = self.pose.x + np.outer(np.cos(angles), steps)
        ys = self.pose.y + np.outer(np.sin(angles), steps)
        columns = ((xs - self.grid.origin[0]) / self.grid.resolution).astype(int)
        rows = ((ys - self.grid.origin[1]) / self.grid.resolution).astype(int)
        inside = (rows >= 0) & (rows < self.grid.shape[0]) & (columns >= 0) & \
            (columns < self.grid.shape[1])
        hit = np.zeros_like(inside)
        hit[inside] = self.grid.occupied[rows[inside], columns[inside]]
        first = np.where(hit.any(axis=1), hit.argmax(axis=1), -1)
        ranges = np.where(first >= 0, steps[np.maximum(first, 0)], np.inf)
        return LaserScan(self._time, -field / 2, field / (beams - 1), 0.05, 10.0, ranges)

    def head(self) -> HeadState:
        return self._head

    def point_head(self, pan: float, tilt: float) -> None:
        self._head = HeadState(pan, tilt)

    def emergency_stop(self, engaged: bool = True) -> None:
        self._stopped = engaged

    @property
    def stopped(self) -> bool:
        return self._stopped

    def speaker(self) -> Speaker:
        return self.speaker_part


@pytest.fixture(scope="module")
def scripted_robot() -> Iterator[tuple[object, ScriptedBody, World]]:
    pytest.importorskip("cv2")
    from homebot.embodied import BodyRobot
    from homebot.navigation.local_planner import MotionSearchPlanner
    from homebot.navigation.localisation import MonteCarloLocalisation

    world = World.load("apartment")
    navigator = Navigator(world)
    body = ScriptedBody(navigator.grid, world.robot.pose)
    localisation = MonteCarloLocalisation(navigator.grid, np.random.default_rng(7))
    localisation.initialise(world.robot.pose, spread=0.05, angle_spread=0.05)
    robot = BodyRobot(body, world, navigator, localisation, MotionSearchPlanner(),
                      EventLog(body.now))
    yield robot, body, world


def test_a_body_robot_drives_through_a_home_over_a_body_with_no_simulation_behind_it(
        scripted_robot: tuple[object, ScriptedBody, World]) -> None:
    from homebot.embodied import BodyRobot

    robot, body, world = scripted_robot
    assert isinstance(robot, BodyRobot)
    goal = world.placements["bed"].approach
    report = robot.move_to(goal)
    assert report.reached, report
    assert math.dist(body.pose.xy(), goal.xy()) < 0.3  # where the body truly is
    assert report.doors_passed  # the way leads through doors it looked at with its laser


def test_a_body_robot_speaks_through_its_bodys_speaker(
        scripted_robot: tuple[object, ScriptedBody, World]) -> None:
    pytest.importorskip("espeakng_loader")
    from homebot.embodied import BodyRobot

    robot, body, _ = scripted_robot
    assert isinstance(robot, BodyRobot)
    robot.say("Hello, I am here.")
    assert body.speaker_part.said[-1] == "Hello, I am here."


def test_a_body_without_a_face_tracker_shows_no_face(
        scripted_robot: tuple[object, ScriptedBody, World]) -> None:
    from homebot.embodied import BodyRobot

    robot, body, _ = scripted_robot
    assert isinstance(robot, BodyRobot)
    with pytest.raises(PartMissing):
        body.face_crops(3)
    assert robot.face_views(3) == []


def _reachable(root: object, stop: object) -> Iterator[object]:
    """Every object reachable from ``root`` through instances' attributes, containers,
    bound methods, closures and partials, not looking inside ``stop`` (the body) or
    inside modules, classes and functions' globals."""
    seen = {id(stop)}
    todo = [root]
    while todo:
        item = todo.pop()
        if id(item) in seen or isinstance(item, (type, types.ModuleType, str, bytes,
                                                 int, float, bool, np.ndarray)):
            continue
        seen.add(id(item))
        yield item
        if isinstance(item, types.FunctionType):
            todo.extend(cell.cell_contents for cell in (item.__closure__ or ())
                        if _filled(cell))
            continue
        todo.extend(gc.get_referents(item))


def _filled(cell: types.CellType) -> bool:
    try:
        cell.cell_contents  # noqa: B018 - an empty cell raises
    except ValueError:
        return False
    return True


def test_the_embodied_robot_reaches_the_simulation_only_through_its_body() -> None:
    """What ``build_run`` hands the embodied robot holds nothing of ``homebot.sim`` (a
    ``Simulation``, a ``SimRobot``, the simulator's hands or people) but the ``SimBody``."""
    pytest.importorskip("mujoco")
    from homebot.app import Fidelity, RunSettings, build_run

    world = World.load("apartment")
    run = build_run(RunSettings(world=world, seed=1, fidelity=Fidelity.EMBODIED))
    robot = run.robot
    leaks = sorted({f"{type(item).__module__}.{type(item).__qualname__}"
                    for item in _reachable(robot, run.body)
                    if type(item).__module__.startswith("homebot.sim")})
    assert leaks == [], f"the robot reaches the simulation through {leaks}"
