"""Forces a simulated person exerts: scripted and seeded profiles, and a hand that grips.

A person in the physics scene touches things in one of two ways:

- a **force profile**: a force over time, scripted or drawn from a seeded generator
  (a pull on a handed-over object, a bump against the robot's hand), applied at a
  point of a body;
- a **gripping hand**: the person's hand follows a scripted trajectory and pulls the
  point it holds towards itself through a spring and damper (guiding the robot by its
  hand, carrying one end of a table, pushing a door).

Either ends as a force in the world frame applied at a point of a MuJoCo body,
through ``MjData.xfrc_applied`` (a force and torque about the body's centre of mass;
``apply_at`` does the lever arm). Everything here is ground truth: the person's
intention (when the pull started) is what the benchmarks judge the robot against, the
robot senses only what reaches its wrist.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = [
    "ForceProfile",
    "ForcePulse",
    "GrippingHand",
    "HandoverTrial",
    "Trajectory",
    "apply_at",
    "handover_trial",
]


def _vector(values: Sequence[float] | np.ndarray) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.shape != (3,) or not np.all(np.isfinite(array)):
        raise ValueError(f"a force or point is three finite numbers, not {values!r}")
    return array


@dataclass(frozen=True)
class ForcePulse:
    """A force that ramps up over ``ramp`` seconds from ``start``, holds, and ramps down
    to nothing by ``end`` (world frame, newtons)."""

    start: float
    end: float
    force: tuple[float, float, float]
    ramp: float = 0.1

    def __post_init__(self) -> None:
        if not (self.end > self.start and self.ramp > 0):
            raise ValueError(f"a pulse ends after it starts and ramps over a positive time: "
                             f"{self}")
        _vector(self.force)

    @property
    def magnitude(self) -> float:
        return float(np.linalg.norm(self.force))

    def scale(self, t: float) -> float:
        """0 … 1: how much of the force acts at time ``t``."""
        if t <= self.start or t >= self.end:
            return 0.0
        ramp = min(self.ramp, (self.end - self.start) / 2)
        return min(1.0, (t - self.start) / ramp, (self.end - t) / ramp)

    def at(self, t: float) -> np.ndarray:
        return self.scale(t) * np.asarray(self.force, dtype=float)


@dataclass(frozen=True)
class ForceProfile:
    """A sum of pulses: the force a person applies over time."""

    pulses: tuple[ForcePulse, ...] = ()

    def at(self, t: float) -> np.ndarray:
        total = np.zeros(3)
        for pulse in self.pulses:
            total += pulse.at(t)
        return total

    def first_above(self, threshold: float, *, step: float = 0.001,
                    until: float | None = None) -> float | None:
        """The first time the force's magnitude exceeds ``threshold`` (None: never)."""
        if not self.pulses:
            return None
        end = until if until is not None else max(p.end for p in self.pulses)
        times = step * np.arange(math.ceil(end / step) + 1)
        total = np.zeros((len(times), 3))
        for pulse in self.pulses:
            ramp = min(pulse.ramp, (pulse.end - pulse.start) / 2)
            scale = np.clip(np.minimum((times - pulse.start) / ramp, (pulse.end - times) / ramp),
                            0.0, 1.0)
            total += scale[:, None] * np.asarray(pulse.force, dtype=float)
        above = np.flatnonzero(np.linalg.norm(total, axis=1) > threshold)
        return float(times[above[0]]) if len(above) else None


@dataclass(frozen=True)
class HandoverTrial:
    """One person at a handover: bumps that stay below the threshold, then perhaps a pull.

    ``pull_above`` is the ground truth the robot is judged by: when the pull's force
    first exceeds the threshold (None: this person never pulls).
    """

    profile: ForceProfile
    threshold: float
    pull_above: float | None
    duration: float
    bumps: int


def handover_trial(rng: np.random.Generator, *, threshold: float, duration: float = 4.0,
                   pull: bool | None = None) -> HandoverTrial:
    """A seeded handover: 0–3 bumps below ``threshold`` in any direction, then (unless
    ``pull`` is False; drawn when None, 80 % pull) a pull of 1.3–3 × the threshold,
    forward (away from the robot), up to 35° off the forward axis, ramping up in
    0.05–0.4 s and lasting 0.8–1.5 s."""
    pulses: list[ForcePulse] = []
    bumps = int(rng.integers(0, 4))
    pulls = bool(rng.random() < 0.8) if pull is None else pull
    pull_start = float(rng.uniform(1.2, duration - 2.0))
    for _ in range(bumps):
        start = float(rng.uniform(0.3, (pull_start - 0.35) if pulls else duration - 0.5))
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        magnitude = float(rng.uniform(0.2, 0.6)) * threshold
        length = float(rng.uniform(0.05, 0.3))
        pulses.append(ForcePulse(start, start + length, tuple(magnitude * direction),
                                 ramp=min(0.05, length / 2)))
    if pulls:
        elevation = float(rng.uniform(-0.2, 0.6))
        azimuth = float(rng.uniform(-0.6, 0.6))
        direction = np.array([math.cos(elevation) * math.cos(azimuth),
                              math.cos(elevation) * math.sin(azimuth), math.sin(elevation)])
        magnitude = float(rng.uniform(1.3, 3.0)) * threshold
        pulses.append(ForcePulse(pull_start, pull_start + float(rng.uniform(0.8, 1.5)),
                                 tuple(magnitude * direction),
                                 ramp=float(rng.uniform(0.05, 0.4))))
    profile = ForceProfile(tuple(pulses))
    above = profile.first_above(threshold) if pulls else None
    return HandoverTrial(profile, threshold, above, duration, bumps)


@dataclass(frozen=True)
class Trajectory:
    """A timed path of a person's hand: ``points[i]`` (x, y, z, world frame) at ``times[i]``;
    straight lines between, standing still before the first and after the last."""

    times: tuple[float, ...]
    points: tuple[tuple[float, float, float], ...]

    def __post_init__(self) -> None:
        if len(self.times) != len(self.points) or not self.times:
            raise ValueError("a trajectory has one time per point, and at least one")
        if any(b < a for a, b in zip(self.times, self.times[1:], strict=False)):
            raise ValueError("a trajectory's times do not go back")

    @classmethod
    def walked(cls, points: Sequence[Sequence[float]], speed: float,
               start: float = 0.0) -> Trajectory:
        """Through ``points`` at a constant ``speed`` (m/s), starting at ``start``."""
        times = [start]
        for a, b in itertools.pairwise(points):
            times.append(times[-1] + math.dist(a, b) / speed)
        return cls(tuple(times), tuple((float(p[0]), float(p[1]), float(p[2]))
                                       for p in points))

    @property
    def end(self) -> float:
        return self.times[-1]

    def at(self, t: float) -> np.ndarray:
        times = self.times
        if t <= times[0]:
            return np.asarray(self.points[0], dtype=float)
        if t >= times[-1]:
            return np.asarray(self.points[-1], dtype=float)
        k = int(np.searchsorted(times, t, side="right")) - 1
        span = times[k + 1] - times[k]
        f = (t - times[k]) / span if span > 0 else 1.0
        a, b = np.asarray(self.points[k], dtype=float), np.asarray(self.points[k + 1], dtype=float)
        result: np.ndarray = a + f * (b - a)
        return result

    def velocity(self, t: float) -> np.ndarray:
        times = self.times
        if t <= times[0] or t >= times[-1]:
            return np.zeros(3)
        k = int(np.searchsorted(times, t, side="right")) - 1
        span = times[k + 1] - times[k]
        if span <= 0:
            return np.zeros(3)
        result: np.ndarray = (np.asarray(self.points[k + 1], dtype=float) -
                              np.asarray(self.points[k], dtype=float)) / span
        return result


@dataclass
class GrippingHand:
    """A person's hand holding a point: it pulls the point towards the hand's scripted
    position through a spring (``stiffness``, N/m) and damper (``damping``, N·s/m),
    with at most ``max_force`` newtons, as an arm pulling on a handle does."""

    trajectory: Trajectory
    stiffness: float = 400.0
    damping: float = 40.0
    max_force: float = 60.0
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))

    def force(self, t: float, point: np.ndarray, velocity: np.ndarray) -> np.ndarray:
        """The force on the held point at ``t`` (world frame)."""
        target = self.trajectory.at(t) + self.offset
        wanted = self.trajectory.velocity(t)
        f = self.stiffness * (target - point) + self.damping * (wanted - velocity)
        norm = float(np.linalg.norm(f))
        if norm > self.max_force:
            f *= self.max_force / norm
        return np.asarray(f, dtype=float)


def apply_at(model: Any, data: Any, body: int, point: np.ndarray, force: np.ndarray) -> None:
    """Add ``force`` (world frame) acting at ``point`` (world frame) on ``body`` to
    ``data.xfrc_applied``, which MuJoCo applies at the body's centre of mass: the lever
    arm from there to the point gives the torque."""
    del model  # the body's centre of mass is in the data
    lever = np.asarray(point, dtype=float) - data.xipos[body]
    data.xfrc_applied[body, :3] += force
    data.xfrc_applied[body, 3:] += np.cross(lever, force)
