"""Localisation trials: seeded drives of the embodied robot, judged against the truth.

The robot's body is simulated (``SimBody``) and its filter (``MonteCarloLocalisation``)
is judged against the simulator's pose of the robot, never against its own belief:

- ``tracking_run`` / ``tracking_drive``: from the known start, a seeded route of
  placements (pure pursuit of the Navigator's path, steered by the *estimate*), the
  position error at every tick;
- ``random_free_pose`` and ``converged_after``: put (or kidnap) the robot at a random pose,
  wander on the laser alone, and the time after which the error stayed below
  ``CONVERGED``.

``homebot bench localisation`` (and ``bench transport`` over ROS 2) run them and print
their figures.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from homebot.geometry import Pose, wrap_angle
from homebot.navigation import Navigator
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.robot import Body, LaserScan, Twist
from homebot.sim.body import SimBody
from homebot.sim.simulation import Simulation
from homebot.world import DoorState, LaserModel, OccupancyGrid, World

__all__ = ["CONVERGED", "DEADLINE", "WALKERS", "LocalisationSetting", "converged_after",
           "lost_and_kidnapped", "position_error", "random_free_pose", "simulated_body",
           "tracking_drive", "tracking_run"]

CONVERGED = 0.20  #: metres: "localised" in the global and kidnapping phases
DEADLINE = 30.0  #: seconds of simulated time to converge
WALKERS = 3



@dataclass
class LocalisationSetting:
    """The home, its grid and planner, and the filter's parameters the trials run with."""

    world: World
    grid: OccupancyGrid
    navigator: Navigator
    parameters: MclParameters = field(default_factory=MclParameters)


##########################################################################################
# Driving without the filter's help (wandering) and with it (following a path)
##########################################################################################


def _clearance_ahead(scan: LaserScan, half_angle: float, quantile: float = 0.0) -> float:
    """The ``quantile`` of the ranges ahead (0: the nearest return)."""
    angles = scan.angles() + scan.mount.theta
    ahead = (np.abs(angles) <= half_angle) & scan.valid()
    return float(np.quantile(scan.ranges[ahead], quantile)) if ahead.any() else scan.range_max


def _front_and_open(scan: LaserScan) -> tuple[float, float]:
    """The clearance ahead (±25°) and the direction (robot frame) of the most open sector."""
    angles = scan.angles() + scan.mount.theta
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
    front = _clearance_ahead(scan, math.radians(25))
    window = 15  # beams: smooth so that a door gap, not a stray long beam, wins
    smooth = np.convolve(ranges, np.ones(window) / window, mode="same")
    sideways = np.abs(angles) <= math.radians(100)
    best = int(np.argmax(np.where(sideways, smooth, -1.0)))
    return front, float(angles[best])


def _wander(scan: LaserScan) -> Twist:
    """Drive towards the most open direction, slowing and turning as the way ahead closes."""
    front, opening = _front_and_open(scan)
    if front < 0.55:
        return Twist(0.0, 0.0, 0.9 if opening >= 0 else -0.9)
    return Twist(min(0.4, 0.5 * (front - 0.45)), 0.0, max(-0.9, min(0.9, 1.5 * opening)))


class _Wanderer:
    """``_wander``, turning on the spot for a while whenever the base has not moved for 1 s
    (pressed against something its laser does not see, such as a table edge)."""

    def __init__(self) -> None:
        self._last: Pose | None = None
        self._still_since = 0.0
        self._turn_until = -1.0

    def command(self, body: SimBody) -> Twist:
        now, odometry = body.now(), body.odometry().pose
        last = self._last
        if last is None or math.hypot(odometry.x - last.x, odometry.y - last.y) > 0.02 or \
                abs(odometry.theta - last.theta) > 0.05:
            self._last, self._still_since = odometry, now
        if now - self._still_since > 1.0:
            self._turn_until, self._still_since = now + 1.5, now
        if now < self._turn_until:
            return Twist(0.0, 0.0, 0.9)
        return _wander(body.scan())


def _pursue(estimate: Pose, target: tuple[float, float], scan: LaserScan) -> Twist:
    """Turn towards ``target`` and drive when facing it; stop short of anything ahead."""
    bearing = math.atan2(target[1] - estimate.y, target[0] - estimate.x) - estimate.theta
    bearing = wrap_angle(bearing)
    turn = max(-1.2, min(1.2, 2.0 * bearing))
    speed = 0.5 * max(0.0, math.cos(bearing)) ** 2 if abs(bearing) < 0.9 else 0.0
    # The median, so that spurious short returns do not stop the robot for nothing.
    if _clearance_ahead(scan, math.radians(12), 0.5) < 0.3:
        speed = 0.0  # someone (or something) right ahead: wait, turning
    return Twist(speed, 0.0, turn)


##########################################################################################
# Trials
##########################################################################################


def simulated_body(setting: LocalisationSetting, seed: int,
                   spurious: float) -> tuple[Simulation, SimBody]:
    """A fresh simulated home and body for ``seed``, with ``spurious`` of the beams spurious."""
    simulation = Simulation(setting.world, seed=seed, navigator=setting.navigator)
    laser = LaserModel(**{**setting.world.robot.laser.model_dump(), "spurious": spurious})
    return simulation, SimBody(simulation, walkers=WALKERS, laser=laser)


def position_error(mcl_pose: Pose, simulation: Simulation) -> float:
    x, y, _ = simulation.robot_pose
    return math.hypot(mcl_pose.x - x, mcl_pose.y - y)


def tracking_run(setting: LocalisationSetting, seed: int, seconds: float,
                  spurious: float) -> tuple[list[float], float]:
    """One seeded drive along placements: the error at every tick, and the distance driven."""
    simulation, body = simulated_body(setting, seed, spurious)
    return tracking_drive(setting, body, lambda: simulation.robot_pose, seed, seconds)


def tracking_drive(setting: LocalisationSetting, body: Body,
                   truth: Callable[[], tuple[float, float, float]], seed: int,
                   seconds: float) -> tuple[list[float], float]:
    """The tracking drive on any body (``SimBody`` in ``tracking_run``, ``RosBody`` in bench
    transport), judged by ``truth`` (the simulator's pose of the robot)."""
    mcl = MonteCarloLocalisation(setting.grid, np.random.default_rng([seed, 11]),
                                 setting.parameters)
    mcl.initialise(Pose(*truth()), 0.05, 0.05)
    route = np.random.default_rng([seed, 12])
    names = sorted(setting.world.placements)
    closed = frozenset(name for name, door in setting.world.doors.items()
                       if door.state is not DoorState.OPEN)
    waypoints: list[tuple[float, float]] = []
    stuck_since = 0.0
    last = truth()
    errors = []
    distance = 0.0
    estimate = mcl.update(body.odometry(), body.scan())
    while body.now() < seconds:
        if not waypoints:
            goal = setting.world.placements[names[int(route.integers(len(names)))]]
            plan = setting.navigator.plan(estimate.xy(), goal.approach.xy(), closed)
            waypoints = list(plan.waypoints[1:]) if plan else []
            continue
        if math.dist(estimate.xy(), waypoints[0]) < 0.3:
            waypoints.pop(0)
            continue
        body.command_velocity(_pursue(estimate, waypoints[0], body.scan()))
        before = truth()
        body.tick()
        after = truth()
        distance += math.dist(before[:2], after[:2])
        estimate = mcl.update(body.odometry(), body.scan())
        errors.append(math.hypot(estimate.x - after[0], estimate.y - after[1]))
        if math.dist(after[:2], last[:2]) > 0.2:
            last, stuck_since = after, body.now()
        elif body.now() - stuck_since > 6.0:  # someone in the way: go elsewhere
            waypoints, stuck_since = [], body.now()
    return errors, distance


def random_free_pose(setting: LocalisationSetting, body: SimBody, rng: np.random.Generator,
                      away_from: tuple[float, float] | None) -> Pose:
    grid = setting.grid
    free = np.flatnonzero(~grid.blocked.ravel())
    closed = body.sim.closed_doors()
    while True:
        row, column = divmod(int(free[rng.integers(free.size)]), grid.shape[1])
        x, y = grid.center_of(row, column)
        if away_from is not None and math.dist((x, y), away_from) < 2.0:
            continue
        if body.geometry.clearance(x, y, closed) < body.radius + 0.1:
            continue
        if any(math.dist((x, y), person.position) < 0.8
               for person in body.sim.people.values()):
            continue
        return Pose(x, y, float(rng.uniform(-math.pi, math.pi)))


def converged_after(body: SimBody, mcl: MonteCarloLocalisation, simulation: Simulation,
           seconds: float) -> float:
    """Wander for ``seconds``; the time (from the start) after which the error stayed small."""
    start = body.now()
    samples: list[tuple[float, float]] = []
    mcl.update(body.odometry(), body.scan())
    wanderer = _Wanderer()
    while body.now() - start < seconds:
        body.command_velocity(wanderer.command(body))
        body.tick()
        estimate = mcl.update(body.odometry(), body.scan())
        samples.append((body.now() - start, position_error(estimate, simulation)))
    bad = [index for index, (_, error) in enumerate(samples) if error >= CONVERGED]
    if not bad:
        return 0.0
    if bad[-1] == len(samples) - 1:
        return math.inf
    return samples[bad[-1] + 1][0]


def lost_and_kidnapped(setting: LocalisationSetting, seed: int,
                       seconds: float) -> tuple[float, float]:
    """Global localisation from a random pose, then a kidnapping to another: each phase's
    ``converged_after`` (``math.inf``: not converged by its end)."""
    simulation, body = simulated_body(setting, seed, 0.0)
    rng = np.random.default_rng([seed, 21])
    body.teleport(random_free_pose(setting, body, rng, None))
    mcl = MonteCarloLocalisation(setting.grid, np.random.default_rng([seed, 22]),
                                 setting.parameters)
    mcl.initialise_globally()
    found = converged_after(body, mcl, simulation, seconds)
    body.teleport(random_free_pose(setting, body, rng, simulation.robot_pose[:2]))
    return found, converged_after(body, mcl, simulation, seconds)
