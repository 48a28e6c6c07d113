"""The Dynamic Window Approach (Fox, Burgard and Thrun 1997): the baseline local controller.

Each cycle samples the velocities the base can reach within one control
period (the dynamic window), simulates each as a circular arc held for
``horizon`` seconds, drops those that would not stop before the nearest
obstacle on their arc (admissible velocities), and picks the one maximising

    G(v, ω) = α · heading + β · clearance + γ · velocity,

each term normalised over the window: ``heading`` is how well the robot
faces the lookahead point at the arc's end, ``clearance`` the distance to the
nearest obstacle on the arc (capped), ``velocity`` the forward speed. The
obstacles come from the same scan-built ``LocalGrid`` as stage 2. A velocity
is admissible when the robot can brake before its footprint (plus
``contact``) touches a return on the arc; the safety margin only shapes the
local path the carrot is taken from (no speed-dependent growth: braking is
what DWA's admissibility checks).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from homebot.errors import LocalPlannerError
from homebot.geometry import Pose, wrap_angles
from homebot.navigation.localmap import LocalGrid, check_request, lookahead, visible_lookahead
from homebot.robot import DriveKind, LaserScan, Twist, VelocityLimits

__all__ = ["DynamicWindowPlanner"]


@dataclass
class DynamicWindowPlanner:
    """DWA over (v, ω) (and vy on an omnidirectional base).

    Args:
        period: the control period (the window is what it allows), seconds.
        horizon: how long each sampled velocity is simulated, seconds.
        samples_linear, samples_angular: window samples per axis.
        heading, clearance, velocity: the objective's weights (α, β, γ).
        clearance_cap: clearance beyond this counts as this, metres.
        lookahead: how far along the path the robot steers for, metres.
        safety: clearance the local path keeps beyond the robot's radius, metres.
        contact: clearance beyond the radius that counts as touching, metres.
    """

    period: float = 0.05
    horizon: float = 1.5
    samples_linear: int = 7
    samples_angular: int = 15
    heading: float = 0.6
    clearance: float = 0.3
    velocity: float = 0.3
    clearance_cap: float = 1.0
    lookahead: float = 1.4
    safety: float = 0.05
    contact: float = 0.04
    grid_size: float = 4.0
    resolution: float = 0.05
    goal_tolerance: float = 0.1
    last_blocked: bool = field(default=False, init=False)
    _inside: float | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        for value, what in ((self.period, "period"), (self.horizon, "horizon"),
                            (self.lookahead, "lookahead"), (self.clearance_cap, "clearance_cap")):
            if not (math.isfinite(value) and value > 0):
                raise LocalPlannerError(f"the DWA planner's {what} must be a positive number, "
                                        f"not {value!r}")
        if self.samples_linear < 2 or self.samples_angular < 2:
            raise LocalPlannerError("the DWA planner needs at least 2 samples per axis")

    def plan(self, pose: Pose, velocity: Twist, scan: LaserScan,
             path: Sequence[tuple[float, float]], limits: VelocityLimits, drive: DriveKind,
             radius: float) -> Twist:
        """The velocity to command now (robot frame); see ``LocalController.plan``."""
        check_request(path, radius)
        grid = LocalGrid.from_scan(scan, self.grid_size, self.resolution)
        grown, self._inside = _grown(grid, radius + self.contact)
        goal, final = lookahead(pose, path, min(self.lookahead, grid.half_size - 0.25))
        # The carrot: the furthest point in straight sight along the local path to the
        # lookahead point (the same local path by length as stage 2's first search).
        field = grid.distance_field(goal, radius + self.safety, pool=1)
        target = visible_lookahead(grid, field, self.lookahead, min(radius, grown))
        if final and math.hypot(goal[0] - target[0], goal[1] - target[1]) < 0.05:
            target = goal
        final = final and target == goal
        omni = drive is DriveKind.OMNIDIRECTIONAL
        dv = limits.linear_acceleration * self.period
        dw = limits.angular_acceleration * self.period
        low = -0.1 if omni else 0.0
        vx = np.linspace(max(velocity.vx - dv, low), min(velocity.vx + dv, limits.linear),
                         self.samples_linear)
        wz = np.linspace(max(velocity.wz - dw, -limits.angular),
                         min(velocity.wz + dw, limits.angular), self.samples_angular)
        if omni:
            vy = np.linspace(max(velocity.vy - dv, -limits.linear),
                             min(velocity.vy + dv, limits.linear), self.samples_linear)
            grid_v = np.meshgrid(vx, vy, wz, indexing="ij")
        else:
            grid_v = np.meshgrid(vx, np.zeros(1), wz, indexing="ij")
        window = np.column_stack([axis.ravel() for axis in grid_v])
        window = window[np.hypot(window[:, 0], window[:, 1]) <= limits.linear + 1e-9]
        score, clear_distance = self._evaluate(window, grid, target, final, limits, grown)
        speed = np.hypot(window[:, 0], window[:, 1])
        # Admissible: able to stop before the nearest obstacle on the arc.
        admissible = speed <= np.sqrt(2 * limits.linear_acceleration * clear_distance)
        if final:
            remaining = math.hypot(*target)
            admissible &= speed <= math.sqrt(2 * limits.linear_acceleration *
                                             max(remaining - 0.02, 0.0)) + 0.05
        self.last_blocked = not admissible.any()
        if self.last_blocked:
            return limits.clip(Twist(max(velocity.vx - dv, 0.0) if velocity.vx > 0 else
                                     min(velocity.vx + dv, 0.0), 0.0, 0.0), drive)
        best = int(np.argmax(np.where(admissible, score, -np.inf)))
        return limits.clip(Twist(float(window[best, 0]), float(window[best, 1]),
                                 float(window[best, 2])), drive)

    def _evaluate(self, window: np.ndarray, grid: LocalGrid, target: tuple[float, float],
                  final: bool, limits: VelocityLimits,
                  grown: float) -> tuple[np.ndarray, np.ndarray]:
        """The objective of each velocity, and the free distance along its arc."""
        steps = max(round(self.horizon / 0.1), 1)
        dt = self.horizon / steps
        n = len(window)
        times = dt * np.arange(1, steps + 1)[:, None]
        th = window[:, 2] * times
        middle = th - window[:, 2] * dt / 2
        cos, sin = np.cos(middle), np.sin(middle)
        x = np.cumsum((window[:, 0] * cos - window[:, 1] * sin) * dt, axis=0)
        y = np.cumsum((window[:, 0] * sin + window[:, 1] * cos) * dt, axis=0)
        absolute = grid.clearance_at(x, y)
        clearance = absolute - grown
        speed = np.hypot(window[:, 0], window[:, 1])
        hit = clearance <= 0.0
        if self._inside is not None:
            # Already too close: only arcs that end no closer than now are free at all.
            hit[0] |= absolute[-1] < self._inside
        first_hit = np.where(hit.any(axis=0), hit.argmax(axis=0), steps)
        # Free distance along the arc before the first contact.
        free = np.where(first_hit < steps, speed * dt * first_hit, np.inf)
        nearest = np.minimum(np.min(clearance, axis=0), self.clearance_cap)
        nearest = np.maximum(nearest, 0.0)
        # Heading at the arc's end towards the target (Fox et al. take the pose after braking).
        bearing = np.arctan2(target[1] - y[-1], target[0] - x[-1])
        error = np.abs(wrap_angles(bearing - th[-1]))
        heading = np.pi - error
        if final:
            # Near the goal, heading matters less than getting there.
            distance = np.hypot(target[0] - x[-1], target[1] - y[-1])
            heading = np.where(distance < 0.3, np.pi - distance, heading)
        velocity = speed / limits.linear
        score = (self.heading * _normalise(heading) + self.clearance * _normalise(nearest) +
                 self.velocity * _normalise(velocity))
        return score, np.broadcast_to(free, (n,)).copy()


def _grown(grid: LocalGrid, grown: float) -> tuple[float, float | None]:
    """The clearance to keep, and the clearance now when the robot is already closer.

    A robot can find itself inside its own margin (a person stepped up, the
    laser's noise); it may then move, but never closer than half a centimetre
    to what it is now, and only so that it ends no closer than it starts.
    """
    start = float(grid.clearance_at(np.zeros(1), np.zeros(1))[0])
    return (grown, None) if start >= grown else (start - 0.005, start)


def _normalise(values: np.ndarray) -> np.ndarray:
    total = float(np.sum(values))
    if total <= 0:
        return np.zeros_like(values)
    result: np.ndarray = values / total
    return result
