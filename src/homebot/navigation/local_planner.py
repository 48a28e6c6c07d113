"""CAESAR's stage 2: A* over the robot's motion commands in a local grid from the scan.

Each control cycle (20 Hz) builds a robot-centred grid from the current laser
scan (``LocalGrid``), grows the obstacles by the robot's radius plus a margin
that rises with the speed a motion would have (CAESAR's dynamic obstacle
extension: the faster the robot, the larger the obstacles), and then searches
in two steps, as CAESAR does:

1. by length: one Dijkstra sweep in the local grid out from the lookahead
   point of the global path gives every cell's remaining path length;
2. by time: A* over sequences of velocity commands, each held for ``step``
   seconds and reachable from the one before within the acceleration limits
   (a lattice of (v, ω), or (vx, vy, ω) on an omnidirectional base). A
   sequence's cost is the time it takes; its heuristic is the least time to
   cover the remaining path length from its end speed, or to turn to the
   path's direction, whichever is longer. A motion is admissible only if the
   robot stays clear of every grown obstacle all along it, by the exact
   distance to the returns wherever the grid's cells are too coarse to tell.

Smooth turning: a sequence also pays, in seconds, for every change of turn
rate along it (``turn_cost``), and its first motion for straying from the turn
rate the cycle before steered for (``hold_cost``, hysteresis; that rate is
also one of the first motions tried). Without these the 20 Hz replanning
flipped between nearly equal plans and the turn rate dithered. Not on the
final approach to the goal, where the goal is to be hit.

The search runs as one compiled kernel (``motion_search.search``). The first
command of the best sequence, moved towards from the current velocity within
one period's acceleration, is the command. Since a faster
motion needs more clearance, the robot slows down near obstacles (Cosero's
collision-aware velocity limits, §4.1) and in doorways. When the lookahead
point is the goal, the speed is capped so the robot can stop on it.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from homebot.errors import LocalPlannerError
from homebot.geometry import Pose
from homebot.navigation.localmap import LocalGrid, check_request, lookahead
from homebot.robot import DriveKind, LaserScan, Twist, VelocityLimits

__all__ = ["MotionSearchPlanner", "PlannerCycle"]

# Fractions of one step's largest velocity change: finer for the first command,
# which is the one executed, coarser deeper in the search.
_FIRST_LINEAR = (-1.0, -0.5, -0.2, 0.0, 0.2, 0.5, 1.0)
_FIRST_ANGULAR = (-1.0, -0.5, -0.2, 0.0, 0.2, 0.5, 1.0)
_DEEP_LINEAR = (-1.0, 0.0, 1.0)
_DEEP_ANGULAR = (-1.0, -0.4, 0.0, 0.4, 1.0)
_OMNI_FIRST = (-1.0, -0.5, 0.0, 0.5, 1.0)
_OMNI_DEEP = (-1.0, 0.0, 1.0)
_POOL = 2  #: the distance field's cells are this many grid cells wide
_FINAL_TURN_COST = 0.1  #: seconds per rad/s of turn-rate change on the final approach


@dataclass(frozen=True, slots=True)
class PlannerCycle:
    """What the last cycle did, for benchmarks and debugging."""

    expansions: int
    depth: int
    blocked: bool  #: no admissible motion: the robot brakes (and turns towards the path)
    target: tuple[float, float]  #: the lookahead point, robot frame


def _validate_positive(value: float, what: str) -> None:
    if not (math.isfinite(value) and value > 0):
        raise LocalPlannerError(f"{what} must be a positive number, not {value!r}")


@dataclass
class MotionSearchPlanner:
    """Stage 2 of CAESAR's collision avoidance (see the module docstring).

    Args:
        period: the control period, seconds (20 Hz).
        step: how long each motion of the lattice is held, seconds.
        depth: how many motions a sequence holds.
        lookahead: how far along the global path the robot steers for, metres.
        safety: clearance kept beyond the robot's radius at a standstill, metres.
        speed_margin: extra clearance per m/s of speed, seconds.
        grid_size: side of the local grid, metres; ``resolution`` its cell size.
        max_expansions: the search's node budget per cycle.
        goal_tolerance: a sequence ending this close to the lookahead point is done.
        greed: the heuristic's weight (weighted A*: 1 is optimal in time, more is faster
            to search at a bounded loss).
        substeps: collision checks per motion.
        batch: nodes expanded together (one vectorised step) from the front of the queue.
        turn_cost: seconds added per rad/s of change in turn rate, so that of two
            equally fast sequences the steadier one wins.
        leg_margin: extra clearance kept from pairs of legs (a person is wider than them).
        hold_cost: seconds added per rad/s the first motion's turn rate differs from the one
            the cycle before chose (hysteresis: no flip-flopping between near-equal plans).
        crawl: m/s: no faster, a motion needs no clearance for its speed (it stops within
            a centimetre) ...
        crawl_allowance: ... and may come this much nearer walls and furniture (returns of
            clusters wider than a leg) than ``safety``: through a doorway met at a slant.
    """

    period: float = 0.05
    step: float = 0.3
    depth: int = 4
    lookahead: float = 1.4
    safety: float = 0.05
    speed_margin: float = 0.25
    grid_size: float = 4.0
    resolution: float = 0.05
    max_expansions: int = 80
    goal_tolerance: float = 0.05
    greed: float = 4.0
    batch: int = 4
    turn_cost: float = 0.3
    leg_margin: float = 0.12
    substeps: int = 3
    hold_cost: float = 1.5
    crawl: float = 0.1
    crawl_allowance: float = 0.02
    last: PlannerCycle | None = field(default=None, init=False)
    _held: tuple[float, float] = field(default=(-math.inf, math.nan), init=False, repr=False)

    def __post_init__(self) -> None:
        for value, what in ((self.period, "period"), (self.step, "step"),
                            (self.lookahead, "lookahead"), (self.grid_size, "grid_size"),
                            (self.resolution, "resolution"),
                            (self.goal_tolerance, "goal_tolerance")):
            _validate_positive(value, f"the local planner's {what}")
        if not (math.isfinite(self.greed) and self.greed >= 1.0):
            raise LocalPlannerError(f"greed must be at least 1, not {self.greed!r}")
        if min(self.depth, self.max_expansions, self.substeps, self.batch) < 1:
            raise LocalPlannerError("depth, max_expansions, substeps and batch must be at "
                                    "least 1")
        if min(self.safety, self.speed_margin, self.turn_cost, self.hold_cost, self.crawl,
               self.crawl_allowance) < 0:
            raise LocalPlannerError("safety, speed_margin, turn_cost, hold_cost, crawl and "
                                    "crawl_allowance cannot be negative")

    def plan(self, pose: Pose, velocity: Twist, scan: LaserScan,
             path: Sequence[tuple[float, float]], limits: VelocityLimits, drive: DriveKind,
             radius: float) -> Twist:
        """The velocity to command now (robot frame); see ``LocalController.plan``."""
        check_request(path, radius)
        grid = LocalGrid.from_scan(scan, self.grid_size, self.resolution, self.leg_margin)
        reach = min(self.lookahead, grid.half_size - 0.25)
        target, final = lookahead(pose, path, reach)
        grown = radius + self.safety
        # Collision-aware speed limits (Cosero): the faster, the more clearance a motion
        # needs, so a cell with little clearance can only be crossed slowly. The field is
        # then the least time to the target (in metres at top speed) along the local path.
        distances = grid.distance_field(target, grown, pool=_POOL,
                                        speed=(self.speed_margin, limits.linear))
        omni = drive is DriveKind.OMNIDIRECTIONAL
        command, expansions, depth = self._search(grid, distances, target, final, limits, omni,
                                                  radius, velocity, scan.stamp)
        self.last = PlannerCycle(expansions, depth, command is None, target)
        if command is None:
            return _towards(velocity, _brake(grid, distances, limits, omni), limits, drive,
                            self.period)
        # Each motion changes the velocity at a constant rate over its step: now, the
        # first motion's velocity one period in.
        share = min(self.period / self.step, 1.0)
        ramped = Twist(velocity.vx + share * (command.vx - velocity.vx),
                       velocity.vy + share * (command.vy - velocity.vy),
                       velocity.wz + share * (command.wz - velocity.wz))
        return _towards(velocity, ramped, limits, drive, self.period)

    def _search(self, grid: LocalGrid, distances: np.ndarray, target: tuple[float, float],
                final: bool, limits: VelocityLimits, omni: bool, radius: float,
                velocity: Twist, stamp: float) -> tuple[Twist | None, int, int]:
        """The search by time (the compiled kernel): the first command, expansions, depth."""
        from homebot.navigation import motion_search  # numba: only once stage 2 plans

        start_clearance = grid.exact_clearance(0.0, 0.0, self.crawl_allowance)
        static = radius + self.safety
        # Already inside the margin (pushed there by a person): do not get any closer.
        # Then it may move, never closer than half a centimetre to what it is now, and
        # only so that each motion ends no closer than it starts.
        inside = start_clearance < static
        if inside:
            static = start_clearance - 0.005
        dv = limits.linear_acceleration * self.step
        dw = limits.angular_acceleration * self.step
        # The turn rate the last cycle steered for, if it was the cycle just before; not on
        # the final approach, where the goal must be hit, not a steady turn kept (kept, it
        # can circle the goal for ever).
        recent = 0 < stamp - self._held[0] <= 1.5 * self.period
        held = self._held[1] if recent and not final else math.nan
        first = _lattice(dv, dw, omni, True)
        if math.isfinite(held) and abs(held - velocity.wz) <= dw:
            # Also the turn rate steered for before, with each speed change: keeping a plan
            # is then possible without dithering round it on the lattice's coarse steps.
            linear = np.unique(first[:, :2], axis=0)
            first = np.vstack((first, np.column_stack(
                (linear, np.full(len(linear), held - velocity.wz)))))
        found, vx, vy, wz, expansions, depth = motion_search.search(
            grid.padded, grid.half_size, grid.resolution, distances, _POOL,
            target[0], target[1], final, velocity.vx, velocity.vy, velocity.wz, omni,
            _spin(velocity), first, _lattice(dv, dw, omni, False),
            static, inside, start_clearance, limits.linear, limits.angular,
            limits.linear_acceleration, limits.angular_acceleration,
            self.step, self.depth, self.max_expansions, self.batch, self.substeps,
            self.goal_tolerance, self.greed, self.speed_margin, self.turn_cost,
            held, self.hold_cost, _FINAL_TURN_COST, grid.returns, grid.starts, grid.per_side,
            grid.bucket, grid.leg_margin, grid.slack, self.crawl, self.crawl_allowance)
        command = Twist(float(vx), float(vy), float(wz)) if found else None
        self._held = (stamp, float(wz) if found else math.nan)
        return command, int(expansions), int(depth)


def _towards(now: Twist, target: Twist, limits: VelocityLimits, drive: DriveKind,
             period: float) -> Twist:
    """``target`` as far as one period's acceleration allows from ``now``, within the limits."""
    linear = limits.linear_acceleration * period
    angular = limits.angular_acceleration * period
    step = Twist(now.vx + max(-linear, min(linear, target.vx - now.vx)),
                 now.vy + max(-linear, min(linear, target.vy - now.vy)),
                 now.wz + max(-angular, min(angular, target.wz - now.wz)))
    return limits.clip(step, drive)


@functools.lru_cache(maxsize=16)
def _lattice(dv: float, dw: float, omni: bool, first: bool) -> np.ndarray:
    """Velocity changes one motion may make, as (n, 3) rows of (dvx, dvy, dwz).

    The same every cycle for one robot: built once (read-only).
    """
    angular = dw * np.asarray(_FIRST_ANGULAR if first else _DEEP_ANGULAR)
    if omni:
        linear = dv * np.asarray(_OMNI_FIRST if first else _OMNI_DEEP)
        turns = angular if first else angular[::2]
        grid = np.meshgrid(linear, linear, turns, indexing="ij")
        lattice = np.column_stack([axis.ravel() for axis in grid])
    else:
        linear = dv * np.asarray(_FIRST_LINEAR if first else _DEEP_LINEAR)
        forward, turn = np.meshgrid(linear, angular, indexing="ij")
        lattice = np.column_stack((forward.ravel(), np.zeros(forward.size), turn.ravel()))
    lattice.setflags(write=False)
    return lattice


def _spin(velocity: Twist) -> float:
    """The way the base turns now (±1), or 0 when it hardly turns."""
    return 0.0 if abs(velocity.wz) < 0.05 else math.copysign(1.0, velocity.wz)


def _brake(grid: LocalGrid, distances: np.ndarray, limits: VelocityLimits, omni: bool) -> Twist:
    """Stop the base; a differential base turns on the spot towards the path meanwhile."""
    if omni:
        return Twist()
    from homebot.navigation import motion_search

    rows, columns = grid.index(np.zeros(1), np.zeros(1))
    direction = float(motion_search.downhill_at(distances, int(rows[0]), int(columns[0]), _POOL))
    if not math.isfinite(direction) or abs(direction) < 0.2:
        return Twist()
    return Twist(0.0, 0.0, math.copysign(min(limits.angular, 2 * abs(direction)), direction))
