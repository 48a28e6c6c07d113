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
   robot stays clear of every grown obstacle all along it.

The first command of the best sequence, moved towards from the current
velocity within one period's acceleration, is the command. Since a faster
motion needs more clearance, the robot slows down near obstacles (Cosero's
collision-aware velocity limits, §4.1) and in doorways. When the lookahead
point is the goal, the speed is capped so the robot can stop on it.
"""

from __future__ import annotations

import functools
import heapq
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from homebot.navigation.localmap import LocalGrid, LocalPlannerError, check_request, lookahead
from homebot.robot import DriveKind, LaserScan, Pose, Twist, VelocityLimits

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
    turn_cost: float = 0.1
    leg_margin: float = 0.12
    substeps: int = 3
    last: PlannerCycle | None = field(default=None, init=False)

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
        if min(self.safety, self.speed_margin, self.turn_cost) < 0:
            raise LocalPlannerError("safety, speed_margin and turn_cost cannot be negative")

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
        allowed = (grid.clearance - grown) / max(self.speed_margin, 1e-6)
        slowness = limits.linear / np.clip(allowed, 0.05, limits.linear)
        distances = grid.distance_field(target, grown, pool=_POOL, slowness=slowness)
        search = _Search(self, grid, distances, target, final, limits, drive, radius, velocity)
        command, expansions, depth = search.run()
        self.last = PlannerCycle(expansions, depth, command is None, target)
        if command is None:
            return _towards(velocity, search.brake(), limits, drive, self.period)
        # Each motion changes the velocity at a constant rate over its step: now, the
        # first motion's velocity one period in.
        share = min(self.period / self.step, 1.0)
        ramped = Twist(velocity.vx + share * (command.vx - velocity.vx),
                       velocity.vy + share * (command.vy - velocity.vy),
                       velocity.wz + share * (command.wz - velocity.wz))
        return _towards(velocity, ramped, limits, drive, self.period)


def _ramp_time(distance: np.ndarray, speed: np.ndarray, top: float,
               acceleration: float) -> np.ndarray:
    """Least time to cover ``distance`` from ``speed`` (may be negative) within ``top``."""
    speed = np.minimum(speed, top)
    ramp_time = (top - speed) / acceleration
    ramp_distance = (top**2 - np.sign(speed) * speed**2) / (2 * acceleration)
    short = (-speed + np.sqrt(np.maximum(speed**2 + 2 * acceleration * distance, 0.0))) / \
        acceleration
    long = ramp_time + (distance - ramp_distance) / top
    result: np.ndarray = np.where(distance <= ramp_distance, short, long)
    return result


def _rest_to_rest(angle: np.ndarray, top: float, acceleration: float) -> np.ndarray:
    """Least time to turn by ``angle`` from rest to rest."""
    result: np.ndarray = np.where(angle <= top**2 / acceleration,
                                  2 * np.sqrt(np.maximum(angle, 0.0) / acceleration),
                                  top / acceleration + angle / top)
    return result


def _turn_time(angle: np.ndarray, rate: np.ndarray, top: float,
               acceleration: float) -> np.ndarray:
    """Least time to turn by ``angle`` (≥ 0) and stop there, turning at ``rate`` towards it now.

    Bang-bang: speed up (to ``top`` at most), slow down; when the turn already
    under way cannot stop in time, stop past the heading and come back.
    """
    toward = np.maximum(rate, 0.0)
    stopping = toward**2 / (2 * acceleration)
    peak = np.sqrt(acceleration * angle + toward**2 / 2)
    triangle = (2 * peak - toward) / acceleration
    cruise = (top - toward) / acceleration + top / acceleration + \
        (angle - (top**2 - toward**2) / (2 * acceleration) - top**2 / (2 * acceleration)) / top
    reachable = np.where(peak <= top, triangle, cruise)
    overshoot = toward / acceleration + _rest_to_rest(stopping - angle, top, acceleration)
    ahead = np.where(stopping <= angle, reachable, overshoot)
    away = np.abs(np.minimum(rate, 0.0))
    back = away / acceleration + _rest_to_rest(angle + away**2 / (2 * acceleration), top,
                                               acceleration)
    result: np.ndarray = np.where(rate >= 0, ahead, back)
    return result


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


@functools.lru_cache(maxsize=4)
def _fractions(substeps: int) -> np.ndarray:
    """(substeps, 1, 1): how far through its motion each substep's middle lies."""
    fraction = ((np.arange(1, substeps + 1) - 0.5) / substeps)[:, None, None]
    fraction.setflags(write=False)
    return fraction


class _Search:
    """One cycle's A* over motion sequences; node states live in preallocated arrays."""

    def __init__(self, planner: MotionSearchPlanner, grid: LocalGrid, distances: np.ndarray,
                 target: tuple[float, float], final: bool, limits: VelocityLimits,
                 drive: DriveKind, radius: float, velocity: Twist) -> None:
        self.p = planner
        self.grid = grid
        self.distances = distances
        self.target = target
        self.final = final
        self.limits = limits
        self.omni = drive is DriveKind.OMNIDIRECTIONAL
        self.velocity = velocity
        self.spin = 0.0 if abs(velocity.wz) < 0.05 else math.copysign(1.0, velocity.wz)
        finite = np.where(np.isfinite(distances), distances, 1e3)
        # The field is constant within each coarse cell: take its slope between them.
        coarse = finite[::_POOL, ::_POOL]
        gradient_rows, gradient_columns = np.gradient(coarse)
        downhill = np.arctan2(-gradient_rows, -gradient_columns)
        self.downhill = np.repeat(np.repeat(downhill, _POOL, axis=0), _POOL, axis=1)
        start_clearance = float(grid.clearance_at(np.zeros(1), np.zeros(1))[0])
        static = radius + planner.safety
        # Already inside the margin (pushed there by a person): do not get any closer.
        # Then it may move, never closer than half a centimetre to what it is now, and
        # only so that each motion ends no closer than it starts.
        self.inside = start_clearance < static
        self.start_clearance = start_clearance
        self.static = static if not self.inside else start_clearance - 0.005
        dv = limits.linear_acceleration * planner.step
        dw = limits.angular_acceleration * planner.step
        self.first_lattice = _lattice(dv, dw, self.omni, True)
        self.deep_lattice = _lattice(dv, dw, self.omni, False)
        self.fraction = _fractions(planner.substeps)
        capacity = 1 + len(self.first_lattice) + (planner.max_expansions + planner.batch) * \
            len(self.deep_lattice)
        # Columns: x, y, theta, vx, vy, wz, remaining path length.
        self.state = np.zeros((capacity, 7))
        self.first = np.zeros(capacity, dtype=np.intp)
        self.depth = np.zeros(capacity, dtype=np.intp)
        self.cost = np.zeros(capacity)
        self.size = 0

    # ---------------------------------------------------------------- the search

    def run(self) -> tuple[Twist | None, int, int]:
        """Best-first over motion sequences; pops up to ``batch`` nodes per vectorised expansion.

        A node whose sequence is ``depth`` motions long, or ends at the target, is
        final: the first one popped wins. Without one within the budget, the
        deepest, then cheapest, node seen wins.
        """
        p = self.p
        v = self.velocity
        self.state[0] = (0.0, 0.0, 0.0, v.vx, v.vy if self.omni else 0.0, v.wz, np.inf)
        self.size = 1
        frontier: list[tuple[float, int]] = [(0.0, 0)]
        best: tuple[int, float, int] | None = None  # (−depth, f, node)
        expansions = 0
        while frontier and expansions < p.max_expansions:
            parents: list[int] = []
            while frontier and len(parents) < p.batch and expansions < p.max_expansions:
                score, node = heapq.heappop(frontier)
                depth = int(self.depth[node])
                if node and (depth >= p.depth or self.state[node, 6] <= p.goal_tolerance):
                    if not parents:
                        return self._command(node), expansions, depth
                    heapq.heappush(frontier, (score, node))  # after this batch
                    break
                parents.append(node)
                expansions += 1
                if node == 0:
                    break  # the root expands alone, with the finer first lattice
            children, scores = self._expand(np.asarray(parents, dtype=np.intp))
            if not len(children):
                continue
            push = heapq.heappush
            for item in zip(scores.tolist(), children.tolist(), strict=True):
                push(frontier, item)
            # The deepest, then cheapest, then first child (children are in node order).
            depths = self.depth[children]
            deepest = np.flatnonzero(depths == depths.max())
            pick = deepest[np.argmin(scores[deepest])]
            key = (-int(depths[pick]), float(scores[pick]), int(children[pick]))
            if best is None or key < best:
                best = key
        if best is None:
            return None, expansions, 0
        return self._command(best[2]), expansions, -best[0]

    def _command(self, node: int) -> Twist:
        vx, vy, wz = self.state[self.first[node], 3:6]
        return Twist(float(vx), float(vy), float(wz))

    def _expand(self, parents: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Add the admissible children of ``parents``; their indices and A* scores."""
        p, limits = self.p, self.limits
        root = parents[0] == 0
        lattice = self.first_lattice if root else self.deep_lattice
        base = self.state[parents]
        size = len(lattice)
        parent = np.repeat(parents, size)
        start = np.repeat(base, size, axis=0)  # (n, 7)
        targets = (base[:, None, 3:6] + lattice[None, :, :]).reshape(-1, 3)
        targets[:, 2] = np.minimum(np.maximum(targets[:, 2], -limits.angular), limits.angular)
        if self.omni:
            # Hardly backwards: the laser sees ahead and to the sides.
            targets[:, 0] = np.minimum(np.maximum(targets[:, 0], -0.1), limits.linear)
            inside = np.hypot(targets[:, 0], targets[:, 1]) <= limits.linear + 1e-9
            targets, start, parent = targets[inside], start[inside], parent[inside]
        else:
            targets[:, 0] = np.minimum(np.maximum(targets[:, 0], 0.0), limits.linear)
        k = p.substeps
        dt = p.step / k
        now = start[:, 3:6]
        change = targets - now
        # Velocity in the middle of each substep, changing at a constant rate: (k, n, 3).
        velocity = now + self.fraction * change
        turn = velocity[:, :, 2] * dt
        th_all = start[:, 2] + np.cumsum(turn, axis=0)
        middle = th_all - turn / 2
        cos, sin = np.cos(middle), np.sin(middle)
        vx, vy = velocity[:, :, 0], velocity[:, :, 1]
        x_all = start[:, 0] + np.cumsum((vx * cos - vy * sin) * dt, axis=0)
        y_all = start[:, 1] + np.cumsum((vx * sin + vy * cos) * dt, axis=0)
        clearance = self.grid.clearance_at(x_all, y_all)
        speed = np.hypot(vx, vy) if self.omni else np.abs(vx)  # equal: vy is 0 then
        ok = np.all(clearance >= self.static + p.speed_margin * speed, axis=0)
        if self.inside:
            ok &= clearance[-1] >= self.start_clearance
        x, y, th = x_all[-1], y_all[-1], th_all[-1]
        end = targets
        rows, columns = self.grid.index(x, y)
        # The field is coarse; the straight distance is a bound that is exact near the target.
        remaining = np.maximum(self.distances[rows, columns],
                               np.hypot(x - self.target[0], y - self.target[1]))
        if self.final:
            # Able to stop on the goal: v² ≤ 2·a·(distance left).
            end_speed = np.hypot(end[:, 0], end[:, 1])
            ok &= end_speed <= np.sqrt(2 * limits.linear_acceleration *
                                       np.maximum(remaining - 0.02, 0.0)) + 0.05
        keep = np.flatnonzero(ok)
        count = len(keep)
        children = np.arange(self.size, self.size + count)
        self.state[children, 0], self.state[children, 1] = x[keep], y[keep]
        self.state[children, 2] = th[keep]
        self.state[children, 3:6] = end[keep]
        self.state[children, 6] = remaining[keep]
        self.first[children] = children if root else self.first[parent[keep]]
        depth = self.depth[parent[keep]] + 1
        self.depth[children] = depth
        self.size += count
        heuristic = self._time_to_go(remaining[keep], end[keep], th[keep], rows[keep],
                                     columns[keep])
        # Time is the cost, plus a little for every change of turn rate (smooth motion).
        cost = self.cost[parent[keep]] + p.step + p.turn_cost * np.abs(change[keep, 2])
        self.cost[children] = cost
        scores: np.ndarray = cost + p.greed * heuristic
        return children, scores

    def _time_to_go(self, remaining: np.ndarray, end: np.ndarray, heading: np.ndarray,
                    rows: np.ndarray, columns: np.ndarray) -> np.ndarray:
        """The time left: cover the distance from this speed, after turning where needed.

        A differential base must also face the way down the distance field; its
        speed counts only along that way.
        """
        limits = self.limits
        if self.omni:
            return _ramp_time(remaining, np.hypot(end[:, 0], end[:, 1]), limits.linear,
                              limits.linear_acceleration)
        error = (self.downhill[rows, columns] - heading + np.pi) % (2 * np.pi) - np.pi
        if self.spin:
            # The way lies behind: either turn will do, so keep turning the way it turns now
            # (otherwise the choice flips from cycle to cycle and the robot dithers).
            error = np.where((np.abs(error) > 2.5) & (error * self.spin < 0),
                             error + self.spin * 2 * np.pi, error)
        error = np.where(remaining > 0.15, error, 0.0)
        along = np.maximum(end[:, 0] * np.cos(error), 0.0)
        travel = _ramp_time(remaining, along, limits.linear, limits.linear_acceleration)
        # Facing more than 45° off the way, a differential base turns on the spot (more or
        # less) before it gets anywhere: that part of the turn adds to the travel.
        turning = _turn_time(np.maximum(np.abs(error) - math.pi / 4, 0.0),
                             end[:, 2] * np.sign(error), limits.angular,
                             limits.angular_acceleration)
        result: np.ndarray = travel + turning
        return result

    # ---------------------------------------------------------------- no way on

    def brake(self) -> Twist:
        """Stop the base; a differential base turns on the spot towards the path meanwhile."""
        if self.omni:
            return Twist()
        rows, columns = self.grid.index(np.zeros(1), np.zeros(1))
        direction = float(self.downhill[rows[0], columns[0]])
        if not math.isfinite(direction) or abs(direction) < 0.2:
            return Twist()
        return Twist(0.0, 0.0, math.copysign(min(self.limits.angular, 2 * abs(direction)),
                                             direction))
