"""Scenes of people walking and crossing in a room, seen by a laser at shin height.

A rectangular room with a few thin furniture legs (chairs, a table: leg-like
clutter), a robot standing at one wall, and 2–5 people who walk between seeded
goals so that their ways cross. People keep a little apart the way a crowd does
(a social repulsion within a metre), walk with a gait (the two legs swing
alternately along the walking direction) and sometimes stop for a while. The
laser is cast exactly against the walls, the furniture legs and the people's
legs (circles), with Gaussian range noise. Ground truth (where each person is)
comes with every frame, for judging a tracker only.

The default laser is a Hokuyo UTM-30LX's (Cosero's): 1081 beams over 270°, 30 m,
1 cm noise; the world's default 1° laser sees a leg at 4 m with one or two beams.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from homebot.geometry import Pose, wrap_angle
from homebot.robot import LaserScan

__all__ = ["CrowdFrame", "CrowdLaser", "CrowdScene", "crowd_scene"]

LEG_RADIUS = 0.06  #: metres (as ``homebot.sim.laser.LEG_RADIUS``)
_ROOM = (8.0, 6.0)  #: metres: the room's width (x) and depth (y), robot at x = 0.3
_HIP = 0.1  #: metres from a person's centre to each leg, across the walking direction
_STRIDE = 0.22  #: metres a leg swings ahead of / behind the centre at full speed
_STEP_LENGTH = 0.7  #: metres walked per gait cycle
_SPEED = (0.5, 1.3)  #: m/s, drawn per person
_PERSONAL = 0.9  #: metres within which people push each other apart
_PUSH = 1.2  #: m/s of repulsion at contact
_STOP_CHANCE = 0.3  #: share of arrivals after which the person stands a while
_STOP = (1.0, 4.0)  #: seconds stood
_ACCELERATION = 2.0  #: m/s², how fast people change their velocity
_POST_RADIUS = (0.015, 0.03)  #: metres: chair and table legs


@dataclass(frozen=True, slots=True)
class CrowdLaser:
    """The laser that watches the crowd."""

    beams: int = 1081
    field_of_view: float = math.radians(270.0)
    range_max: float = 30.0
    noise: float = 0.01


@dataclass(frozen=True)
class CrowdFrame:
    """One sweep and the truth at its time: each person's centre on the map."""

    stamp: float
    scan: LaserScan
    people: dict[str, tuple[float, float]]


@dataclass(frozen=True)
class CrowdScene:
    """A seeded scene: the robot's pose on the map (it stands still) and the frames."""

    robot: Pose
    frames: list[CrowdFrame]
    posts: np.ndarray  #: (n, 3) furniture legs: x, y, radius


@dataclass
class _Walker:
    name: str
    position: np.ndarray
    speed: float
    goal: np.ndarray
    phase: float
    heading: float
    resting_until: float = 0.0
    pace: float = 0.0  #: m/s walked in the last step
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(2))


def crowd_scene(seed: int, people: int, *, seconds: float = 20.0, rate: float = 10.0,
                laser: CrowdLaser | None = None) -> CrowdScene:
    """A scene of ``people`` walkers for ``seconds`` at ``rate`` sweeps a second."""
    if not 1 <= people <= 12:
        raise ValueError(f"people must be 1 to 12, not {people}")
    rng = np.random.default_rng([seed, 15_2])
    laser = laser or CrowdLaser()
    _width, depth = _ROOM
    robot = Pose(0.3, depth / 2, 0.0)
    posts = _furniture(rng)
    walkers = [_Walker(f"person{i}", _free_spot(rng, posts), float(rng.uniform(*_SPEED)),
                       np.zeros(2), float(rng.uniform(0, 2 * math.pi)), 0.0)
               for i in range(people)]
    for walker in walkers:
        walker.goal = _crossing_goal(rng, walker.position, posts)
        walker.heading = _heading(walker.goal - walker.position)
    angles = -laser.field_of_view / 2 + laser.field_of_view / (laser.beams - 1) * np.arange(
        laser.beams)
    directions = np.column_stack((np.cos(angles), np.sin(angles)))
    dt = 1.0 / rate
    frames = []
    for index in range(round(seconds * rate)):
        stamp = index * dt
        if index:
            _step(walkers, dt, stamp, rng, posts)
        legs = np.array([leg for walker in walkers for leg in _legs(walker)])
        ranges = _cast((robot.x, robot.y), directions, posts, legs)
        noisy = ranges + rng.normal(0.0, laser.noise, ranges.shape)
        noisy[ranges > laser.range_max] = np.inf
        scan = LaserScan(stamp, float(angles[0]), float(angles[1] - angles[0]), 0.05,
                         laser.range_max, noisy, Pose(0.0, 0.0, 0.0))
        frames.append(CrowdFrame(stamp, scan, {w.name: (float(w.position[0]),
                                                        float(w.position[1]))
                                               for w in walkers}))
    return CrowdScene(robot, frames, posts)


def _furniture(rng: np.random.Generator) -> np.ndarray:
    """A table (four legs) and two chairs (four legs each) at seeded places."""
    posts = []
    for size in (0.8, 0.42, 0.42):
        cx, cy = rng.uniform(2.5, _ROOM[0] - 1.0), rng.uniform(1.0, _ROOM[1] - 1.0)
        radius = rng.uniform(*_POST_RADIUS)
        for sx in (-1, 1):
            for sy in (-1, 1):
                posts.append((cx + sx * size / 2, cy + sy * size / 2, radius))
    return np.asarray(posts)


def _free_spot(rng: np.random.Generator, posts: np.ndarray) -> np.ndarray:
    width, depth = _ROOM
    for _ in range(100):
        spot = np.array([rng.uniform(1.5, width - 0.5), rng.uniform(0.5, depth - 0.5)])
        if np.all(np.hypot(posts[:, 0] - spot[0], posts[:, 1] - spot[1]) > 0.7):
            return spot
    return np.array([width / 2, depth / 2])


def _crossing_goal(rng: np.random.Generator, here: np.ndarray, posts: np.ndarray) -> np.ndarray:
    """A goal across the room from ``here``, so that people's ways cross its middle."""
    middle = np.array([_ROOM[0] / 2 + 0.5, _ROOM[1] / 2])
    for _ in range(20):
        goal = _free_spot(rng, posts)
        if np.dot(goal - middle, here - middle) < 0 and np.linalg.norm(goal - here) > 2.5:
            return goal
    return _free_spot(rng, posts)


def _heading(vector: np.ndarray) -> float:
    return math.atan2(float(vector[1]), float(vector[0]))


def _step(walkers: list[_Walker], dt: float, now: float, rng: np.random.Generator,
          posts: np.ndarray) -> None:
    velocities = []
    for walker in walkers:
        if now < walker.resting_until:
            velocities.append(np.zeros(2))
            continue
        to_goal = walker.goal - walker.position
        distance = float(np.linalg.norm(to_goal))
        if distance < 0.2:
            if rng.random() < _STOP_CHANCE:
                walker.resting_until = now + rng.uniform(*_STOP)
            walker.goal = _crossing_goal(rng, walker.position, posts)
            velocities.append(np.zeros(2))
            continue
        velocity = to_goal / distance * walker.speed
        for other in walkers:
            if other is walker:
                continue
            away = walker.position - other.position
            gap = float(np.linalg.norm(away))
            if 1e-6 < gap < _PERSONAL:
                velocity = velocity + away / gap * _PUSH * (1.0 - gap / _PERSONAL)
        for x, y, radius in posts:
            away = walker.position - np.array([x, y])
            gap = float(np.linalg.norm(away))
            if 1e-6 < gap < 0.5 + radius:
                velocity = velocity + away / gap * _PUSH * (1.0 - gap / (0.5 + radius))
        speed = float(np.linalg.norm(velocity))
        if speed > 1.5 * walker.speed:
            velocity = velocity * (1.5 * walker.speed / speed)
        velocities.append(velocity)
    for walker, wanted in zip(walkers, velocities, strict=True):
        # people speed up, slow down and turn with a bounded acceleration
        change = wanted - walker.velocity
        size = float(np.linalg.norm(change))
        if size > _ACCELERATION * dt:
            change = change * (_ACCELERATION * dt / size)
        velocity = walker.velocity = walker.velocity + change
        speed = float(np.linalg.norm(velocity))
        if speed > 1e-6:
            # people turn smoothly: heading follows the velocity at most 4 rad/s
            turn = wrap_angle(_heading(velocity) - walker.heading)
            walker.heading += max(-4.0 * dt, min(4.0 * dt, turn))
        walker.phase += 2 * math.pi * speed * dt / _STEP_LENGTH
        walker.pace = speed
        position = walker.position + velocity * dt
        position[0] = min(max(position[0], 0.9), _ROOM[0] - 0.3)
        position[1] = min(max(position[1], 0.3), _ROOM[1] - 0.3)
        walker.position = position


def _legs(walker: _Walker) -> list[tuple[float, float]]:
    """Both legs: apart across the walking direction, swinging along it in opposite phase."""
    swing = _STRIDE * math.sin(walker.phase) * min(1.0, walker.pace / walker.speed)
    along = np.array([math.cos(walker.heading), math.sin(walker.heading)])
    across = np.array([-along[1], along[0]])
    return [tuple(walker.position + side * (_HIP * across + swing * along))
            for side in (-1.0, 1.0)]


def _cast(origin: tuple[float, float], directions: np.ndarray, posts: np.ndarray,
          legs: np.ndarray) -> np.ndarray:
    """Distance along each ray to the room's walls, furniture legs and people's legs."""
    ranges = _walls(origin, directions)
    circles = np.vstack((posts, np.column_stack((legs, np.full(len(legs), LEG_RADIUS)))))
    to_centre = circles[:, :2] - np.asarray(origin)
    along = directions @ to_centre.T  # (beams, circles)
    squared = np.sum(to_centre ** 2, axis=1)[None, :] - along ** 2
    radius2 = circles[:, 2][None, :] ** 2
    inside = squared <= radius2
    entry = along - np.sqrt(np.where(inside, radius2 - squared, 0.0))
    entry = np.where(inside & (entry > 0), entry, np.inf)
    hits: np.ndarray = np.minimum(ranges, entry.min(axis=1))
    return hits


def _walls(origin: tuple[float, float], directions: np.ndarray) -> np.ndarray:
    """Distance along each ray to the inside of the room's rectangle."""
    with np.errstate(divide="ignore", invalid="ignore"):
        tx = np.where(directions[:, 0] > 0, (_ROOM[0] - origin[0]) / directions[:, 0],
                      np.where(directions[:, 0] < 0, -origin[0] / directions[:, 0], np.inf))
        ty = np.where(directions[:, 1] > 0, (_ROOM[1] - origin[1]) / directions[:, 1],
                      np.where(directions[:, 1] < 0, -origin[1] / directions[:, 1], np.inf))
    walls: np.ndarray = np.minimum(tx, ty)
    return walls
