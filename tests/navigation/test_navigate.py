"""``NavigateToPose``: reaching, feedback, cancel, blocked and timed-out goals, bad goals."""

from __future__ import annotations

import math

import pytest
from fake_body import FakeBody, wall

from homebot.errors import NavigationError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.navigate import (
    NavigateToPose,
    NavigationFeedback,
    NavigationGoal,
    OdometryPose,
    StopReason,
)
from homebot.robot import ActionStatus
from homebot.world import World


def _truth(body: FakeBody) -> OdometryPose:
    # The fake's odometry is exact, so anchored odometry is the truth.
    return OdometryPose(body, body.pose)


def test_reaches_the_target_and_faces_its_heading() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    feedback: list[NavigationFeedback] = []
    goal = NavigationGoal(Pose(1.5, 0.5, math.pi / 2), ((0.0, 0.0), (1.5, 0.5)))
    action = NavigateToPose(goal, body, MotionSearchPlanner(), _truth(body),
                            on_feedback=feedback.append)
    result = action.run(max_steps=1000)
    assert action.status is ActionStatus.SUCCEEDED
    assert result.reached and result.reason is StopReason.REACHED
    assert math.dist(body.pose.xy(), (1.5, 0.5)) <= 0.1
    assert abs(math.remainder(body.pose.theta - math.pi / 2, 2 * math.pi)) <= 0.2
    assert body.velocity.is_zero()
    assert 1.5 <= result.travelled <= 2.5
    assert feedback[0].distance_remaining > feedback[-1].distance_remaining


def test_cancel_stops_the_base() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    goal = NavigationGoal(Pose(5.0, 0.0, 0.0), ((0.0, 0.0), (5.0, 0.0)))
    action = NavigateToPose(goal, body, MotionSearchPlanner(), _truth(body))
    for _ in range(30):
        action.step()
    assert body.velocity.vx > 0.2
    action.cancel()
    assert action.step() is ActionStatus.CANCELED
    assert body.velocity.is_zero() and body.command.is_zero()
    result = action.result()
    assert not result.reached and result.reason is StopReason.CANCELED
    assert action.step() is ActionStatus.CANCELED  # stays cancelled


def test_a_walled_in_target_ends_blocked_without_touching_anything() -> None:
    ring = [post for side in ((2.5, -1.0, 2.5, 1.0), (2.5, 1.0, 4.5, 1.0), (2.5, -1.0, 4.5, -1.0),
                              (4.5, -1.0, 4.5, 1.0)) for post in wall(*side)]
    body = FakeBody(Pose(0.0, 0.0, 0.0), ring)
    goal = NavigationGoal(Pose(3.5, 0.0, 0.0), ((0.0, 0.0), (3.5, 0.0)))
    action = NavigateToPose(goal, body, MotionSearchPlanner(), _truth(body), stuck_after=3.0)
    result = action.run(max_steps=2000)
    assert action.status is ActionStatus.ABORTED
    assert result.reason is StopReason.BLOCKED and not result.reached
    assert body.collisions == 0 and body.velocity.is_zero()


def test_the_time_budget_ends_a_long_drive() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    goal = NavigationGoal(Pose(8.0, 0.0, 0.0), ((0.0, 0.0), (8.0, 0.0)), timeout=2.0)
    result = NavigateToPose(goal, body, MotionSearchPlanner(), _truth(body)).run(1000)
    assert result.reason is StopReason.TIMEOUT
    assert 2.0 <= result.duration < 4.0


@pytest.mark.parametrize("options, message", [
    ({"path": ()}, "at least one waypoint"),
    ({"tolerance": 0.0}, "tolerance"),
    ({"timeout": math.nan}, "timeout"),
    ({"target": Pose(math.inf, 0.0)}, "not finite"),
])
def test_bad_goals_are_refused(options: dict[str, object], message: str) -> None:
    arguments: dict[str, object] = {"target": Pose(1.0, 0.0), "path": ((0.0, 0.0), (1.0, 0.0))}
    arguments.update(options)
    with pytest.raises(NavigationError, match=message):
        NavigationGoal(**arguments)  # type: ignore[arg-type]


def test_bad_stuck_time_is_refused() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    goal = NavigationGoal(Pose(1.0, 0.0), ((0.0, 0.0), (1.0, 0.0)))
    with pytest.raises(NavigationError, match="stuck_after"):
        NavigateToPose(goal, body, MotionSearchPlanner(), stuck_after=0.0)


def test_planned_goal_follows_stage_one_or_says_there_is_no_path(
        apartment: World, apartment_navigator: Navigator) -> None:
    start = apartment.placements["couch"].approach
    bed = apartment.placements["bed"].approach
    goal = NavigationGoal.planned(apartment_navigator, start, bed)
    assert goal.path[0] == start.xy() and goal.path[-1] == bed.xy()
    with pytest.raises(NavigationError, match="no path"):
        NavigationGoal.planned(apartment_navigator, start, bed, frozenset({"bedroom door"}))
