"""``NavigateToPose``: drive a body along a global path with a local controller, as an action.

Like Nav2's ``navigate_to_pose`` action (and the Care-O-bot's SMACH move
states): the goal is a target pose and the global path to it; every step
reads the scan, the odometry and the pose estimate, asks the local
controller for a velocity, commands it and lets one control period pass.
Feedback gives the pose and the distance still to go; the result says
whether the target was reached and, if not, why the robot stopped: no
progress for ``stuck_after`` seconds (blocked), the time budget spent
(timeout), or a cancel. Stopping always brings the base to rest first.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from enum import StrEnum

from homebot.errors import NavigationError
from homebot.geometry import Pose, wrap_angle
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigator import Navigator, polyline_length
from homebot.robot import Action, ActionStatus, Body, Twist

__all__ = [
    "NavigateToPose",
    "NavigationFeedback",
    "NavigationGoal",
    "NavigationResult",
    "OdometryPose",
    "StopReason",
]

# Progress smaller than this (metres of remaining distance) does not count against being stuck.
_PROGRESS = 0.1
# Ticks allowed for the base to come to rest when stopping.
_STOP_TICKS = 60


class StopReason(StrEnum):
    """Why a navigation ended."""

    REACHED = "reached"  #: within tolerance of the target
    BLOCKED = "blocked"  #: no progress for a while (a person in the way, a shut door)
    TIMEOUT = "timeout"  #: the time budget ran out
    CANCELED = "canceled"  #: someone cancelled the goal


@dataclass(frozen=True)
class NavigationGoal:
    """Where to go (map frame) and the global path there (the target's position last).

    Args:
        target: the pose to reach.
        path: stage 1's waypoints from (about) the robot to the target.
        tolerance: how close the position must come, metres.
        heading_tolerance: how closely to face ``target.theta`` at the end, radians
            (None: any heading).
        timeout: the simulated time budget, seconds (None: from the path's length).
    """

    target: Pose
    path: tuple[tuple[float, float], ...]
    tolerance: float = 0.1
    heading_tolerance: float | None = 0.2
    timeout: float | None = None

    def __post_init__(self) -> None:
        if not self.path:
            raise NavigationError("a navigation goal needs a path with at least one waypoint; "
                                  "plan one with NavigationGoal.planned")
        if not (math.isfinite(self.tolerance) and self.tolerance > 0):
            raise NavigationError(f"the goal tolerance must be a positive number of metres, "
                                  f"not {self.tolerance!r}")
        if self.timeout is not None and not (math.isfinite(self.timeout) and self.timeout > 0):
            raise NavigationError(f"the timeout must be a positive number of seconds, "
                                  f"not {self.timeout!r}")
        if not all(math.isfinite(v) for v in (self.target.x, self.target.y, self.target.theta)):
            raise NavigationError(f"the target pose {self.target} is not finite")

    @classmethod
    def planned(cls, navigator: Navigator, start: Pose, target: Pose,
                closed_doors: frozenset[str] = frozenset(), **options: float | None
                ) -> NavigationGoal:
        """A goal with stage 1's path from ``start``; ``NavigationError`` when there is none."""
        plan = navigator.plan(start.xy(), target.xy(), closed_doors)
        if plan is None:
            raise NavigationError(f"no path from ({start.x:.2f}, {start.y:.2f}) to "
                                  f"({target.x:.2f}, {target.y:.2f}) on the map; "
                                  "is the target inside furniture, a wall or behind a shut door?")
        return cls(target, plan.waypoints, **options)  # type: ignore[arg-type]

    def path_length(self) -> float:
        return polyline_length(self.path)


@dataclass(frozen=True, slots=True)
class NavigationFeedback:
    """Where the robot believes it is and how far it still has to go along the path."""

    pose: Pose
    distance_remaining: float
    elapsed: float


@dataclass(frozen=True, slots=True)
class NavigationResult:
    """How a navigation ended."""

    reached: bool
    reason: StopReason | None  #: None while the action still runs
    pose: Pose  #: the pose estimate at the end
    travelled: float  #: metres driven (by odometry)
    duration: float  #: simulated seconds

    def __bool__(self) -> bool:
        return self.reached


class OdometryPose:
    """A pose source from odometry alone, anchored at a known map pose (it drifts)."""

    def __init__(self, body: Body, start: Pose) -> None:
        self.body = body
        self.start = start
        self.origin = body.odometry().pose

    def __call__(self) -> Pose:
        # the way driven since the start, by odometry, laid down at the start's map pose
        return self.start.compose(self.body.odometry().pose.relative_to(self.origin))


class NavigateToPose(Action[NavigationGoal, NavigationFeedback, NavigationResult]):
    """Drive ``body`` to ``goal.target`` along ``goal.path`` with ``controller``.

    Args:
        goal: the target and the global path.
        body: the robot's body; each step ticks it once.
        controller: the local controller (stage 2 or DWA).
        pose: the localisation estimate, map frame (e.g. MCL's); default: odometry
            anchored at the path's first waypoint facing along it.
        stuck_after: seconds without progress before giving up as blocked.
        on_feedback: receives every feedback.
    """

    def __init__(self, goal: NavigationGoal, body: Body, controller: LocalController,
                 pose: Callable[[], Pose] | None = None, *, stuck_after: float = 15.0,
                 on_feedback: Callable[[NavigationFeedback], None] | None = None) -> None:
        super().__init__(goal, on_feedback)
        if not (math.isfinite(stuck_after) and stuck_after > 0):
            raise NavigationError(f"stuck_after must be a positive number of seconds, "
                                  f"not {stuck_after!r}")
        self.body = body
        self.controller = controller
        self.pose = pose if pose is not None else OdometryPose(body, _path_start(goal.path))
        self.stuck_after = stuck_after
        self.started = body.now()
        length = goal.path_length()
        self.timeout = goal.timeout if goal.timeout is not None else \
            30.0 + 4.0 * length / body.limits.linear
        self.reason: StopReason | None = None
        self.travelled = 0.0
        self._last_odometry = body.odometry().pose
        self._best_remaining = math.inf
        self._progress_at = self.started
        self._last_pose = self.pose()

    # ---------------------------------------------------------------- the action

    def _step(self) -> ActionStatus | None:
        body, goal = self.body, self.goal
        pose = self.pose()
        self._last_pose = pose
        remaining = _remaining(pose, goal.path, goal.target)
        elapsed = body.now() - self.started
        self.publish_feedback(NavigationFeedback(pose, remaining, elapsed))
        distance = math.dist(pose.xy(), goal.target.xy())
        if distance <= goal.tolerance:
            return self._arrive(pose)
        if remaining < self._best_remaining - _PROGRESS:
            self._best_remaining = remaining
            self._progress_at = body.now()
        if body.now() - self._progress_at >= self.stuck_after:
            return self._end(StopReason.BLOCKED, ActionStatus.ABORTED)
        if elapsed >= self.timeout:
            return self._end(StopReason.TIMEOUT, ActionStatus.ABORTED)
        odometry = body.odometry()
        command = self.controller.plan(pose, odometry.twist, body.scan(), goal.path, body.limits,
                                       body.drive, body.radius)
        body.command_velocity(command)
        self._tick()
        return None

    def _arrive(self, pose: Pose) -> ActionStatus | None:
        """At the target: come to rest, then turn to face the target's heading."""
        body, goal = self.body, self.goal
        velocity = body.odometry().twist
        error = wrap_angle(goal.target.theta - pose.theta)
        aligned = goal.heading_tolerance is None or abs(error) <= goal.heading_tolerance
        resting = abs(velocity.vx) < 1e-3 and abs(velocity.vy) < 1e-3
        if aligned and resting and abs(velocity.wz) < 1e-2:
            self.reason = StopReason.REACHED
            return ActionStatus.SUCCEEDED
        turn = 0.0
        if not aligned:
            # Slow enough near the end to stop within the tolerance.
            limit = math.sqrt(2 * body.limits.angular_acceleration * abs(error))
            turn = math.copysign(min(body.limits.angular, limit, 2.0 * abs(error)), error)
        body.command_velocity(Twist(0.0, 0.0, turn))
        self._tick()
        return None

    def _end(self, reason: StopReason, status: ActionStatus) -> ActionStatus:
        self.reason = reason
        self._stop_base()
        return status

    def _on_cancel(self) -> None:
        if self.reason is None:
            self.reason = StopReason.CANCELED
        self._stop_base()

    def result(self) -> NavigationResult:
        return NavigationResult(self.reason is StopReason.REACHED, self.reason, self._last_pose,
                                round(self.travelled, 3), round(self.body.now() - self.started, 3))

    # ---------------------------------------------------------------- helpers

    def _tick(self) -> None:
        self.body.tick()
        now = self.body.odometry().pose
        self.travelled += math.dist(now.xy(), self._last_odometry.xy())
        self._last_odometry = now

    def _stop_base(self) -> None:
        """Command zero velocity and let the base come to rest."""
        self.body.command_velocity(Twist())
        for _ in range(_STOP_TICKS):
            if self.body.odometry().twist.is_zero():
                break
            self._tick()


def _path_start(path: Sequence[tuple[float, float]]) -> Pose:
    if len(path) >= 2:
        (x0, y0), (x1, y1) = path[0], path[1]
        return Pose(x0, y0, math.atan2(y1 - y0, x1 - x0))
    return Pose(path[0][0], path[0][1], 0.0)


def _remaining(pose: Pose, path: Sequence[tuple[float, float]], target: Pose) -> float:
    """Distance left along ``path`` from the point on it nearest to ``pose``, to the target."""
    best, best_index, best_point = math.inf, len(path) - 1, path[-1]
    for index, (a, b) in enumerate(itertools.pairwise(path)):
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = dx * dx + dy * dy
        t = 0.0 if length == 0 else max(0.0, min(1.0, ((pose.x - a[0]) * dx +
                                                       (pose.y - a[1]) * dy) / length))
        point = (a[0] + t * dx, a[1] + t * dy)
        gap = math.dist(point, pose.xy())
        if gap < best:
            best, best_index, best_point = gap, index, point
    ahead = math.dist(best_point, path[best_index + 1]) if best_index + 1 < len(path) else 0.0
    ahead += sum(math.dist(a, b) for a, b in itertools.pairwise(path[best_index + 1:]))
    return best + ahead + math.dist(path[-1], target.xy())


