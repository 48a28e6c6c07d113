"""Stage 2 (A* over motion commands) and the DWA baseline on a fake body with a ray-cast laser."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from fake_body import FakeBody, wall

from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localmap import LocalController, LocalGrid, LocalPlannerError
from homebot.robot import DriveKind, Pose, Twist

PLANNERS = [MotionSearchPlanner, DynamicWindowPlanner]


def _drive(body: FakeBody, planner: LocalController, path: list[tuple[float, float]],
           seconds: float = 30.0) -> bool:
    """Drive until within 0.1 m of the path's end (by the fake's truth); whether it got there."""
    for _ in range(int(seconds / body.tick_period)):
        if math.dist(body.pose.xy(), path[-1]) <= 0.1:
            return True
        command = planner.plan(body.pose, body.velocity, body.scan(), path, body.limits,
                               body.drive, body.radius)
        body.command_velocity(command)
        body.tick()
    return False


@pytest.mark.parametrize("planner", PLANNERS)
def test_reaches_a_goal_in_open_space(planner: type[LocalController]) -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    assert _drive(body, planner(), [(0.0, 0.0), (3.0, 1.0)])
    assert body.collisions == 0


@pytest.mark.parametrize("planner", PLANNERS)
def test_goes_round_an_obstacle_on_the_path(planner: type[LocalController]) -> None:
    # A person-sized obstacle right on the straight path, and a wall behind it to one side.
    body = FakeBody(Pose(0.0, 0.0, 0.0), [(2.0, 0.0, 0.25), *wall(2.0, 0.9, 2.0, 2.0)])
    assert _drive(body, planner(), [(0.0, 0.0), (4.0, 0.0)])
    assert body.collisions == 0
    assert body.min_clearance >= body.radius


def test_stage2_slows_down_near_obstacles() -> None:
    planner = MotionSearchPlanner()
    fast = FakeBody(Pose(0.0, 0.0, 0.0))
    tight = FakeBody(Pose(0.0, 0.0, 0.0), [*wall(-1.0, 0.37, 3.0, 0.37), *wall(-1.0, -0.37, 3.0,
                                                                              -0.37)])
    speeds = []
    for body in (fast, tight):
        body.velocity = Twist(0.5, 0.0, 0.0)
        command = planner.plan(body.pose, body.velocity, body.scan(), [(0.0, 0.0), (3.0, 0.0)],
                               body.limits, body.drive, body.radius)
        speeds.append(command.vx)
    assert speeds[0] == pytest.approx(0.5)
    assert speeds[1] < 0.5  # a corridor barely wider than the robot: brake


@pytest.mark.parametrize("planner", PLANNERS)
def test_commands_respect_the_acceleration_limits(planner: type[LocalController]) -> None:
    body = FakeBody(Pose(0.0, 0.0, math.pi / 2))
    _drive(body, planner(), [(0.0, 0.0), (2.0, -1.0)], seconds=3.0)
    previous = Twist()
    for command in body.commands:
        assert abs(command.vx - previous.vx) <= body.limits.linear_acceleration * 0.05 + 1e-9
        assert abs(command.wz - previous.wz) <= body.limits.angular_acceleration * 0.05 + 1e-9
        previous = command


def test_stage2_drives_an_omnidirectional_base_round_an_obstacle() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0), [(1.5, 0.0, 0.3)], drive=DriveKind.OMNIDIRECTIONAL)
    assert _drive(body, MotionSearchPlanner(), [(0.0, 0.0), (3.0, 0.0)])
    assert body.collisions == 0


@pytest.mark.parametrize("drive", [DriveKind.DIFFERENTIAL, DriveKind.OMNIDIRECTIONAL])
def test_stage2_compiled_search_is_its_plain_python(drive: DriveKind,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    # One implementation: the numba kernel's own Python function gives the same commands.
    pytest.importorskip("numba")
    from homebot.navigation import motion_search

    body = FakeBody(Pose(0.0, 0.0, 0.3), [(1.2, 0.1, 0.25), *wall(1.0, 0.8, 3.0, 0.8)],
                    drive=drive)
    path = [(0.0, 0.0), (3.0, 0.0)]
    planner = MotionSearchPlanner()
    for velocity in (Twist(), Twist(0.4, 0.0, -0.3), Twist(0.1, 0.0, 0.8)):
        args = (body.pose, velocity, body.scan(), path, body.limits, body.drive, body.radius)
        compiled = planner.plan(*args)
        with monkeypatch.context() as patch:
            patch.setattr(motion_search, "search", motion_search.search.py_func)
            plain = planner.plan(*args)
        assert plain == compiled
        assert planner.last is not None and planner.last.expansions > 1


def test_stage2_turns_steadily() -> None:
    # Round two posts, under a wall: the turn rate changes far less in all (Σ|Δω|) than
    # with neither the cost on changing it nor the hysteresis between cycles.
    path = [(0.0, 0.0), (2.0, 0.6), (5.0, 0.0)]
    obstacles = [(1.5, 0.3, 0.2), (2.8, -0.4, 0.2), *wall(0.0, 1.2, 5.0, 1.2)]
    changes = []
    for planner in (MotionSearchPlanner(), MotionSearchPlanner(turn_cost=0.1, hold_cost=0.0)):
        body = FakeBody(Pose(0.0, 0.0, 0.0), obstacles)
        assert _drive(body, planner, path)
        assert body.collisions == 0
        turns = [command.wz for command in body.commands]
        changes.append(sum(abs(b - a) for a, b in itertools.pairwise(turns)))
    assert changes[0] < 0.8 * changes[1]


def test_local_grid_marks_returns_and_their_clearance() -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0), [(1.3, 0.0, 0.4)])
    grid = LocalGrid.from_scan(body.scan())
    near = grid.clearance_at(np.array([0.9, 0.0, 5.0]), np.array([0.0, 0.0, 0.0]))
    assert near[0] < 0.04  # on the obstacle's surface
    assert near[1] == pytest.approx(0.9, abs=0.04)
    assert near[2] == grid.outside  # beyond the grid nothing is known


def test_legs_are_kept_further_away_than_walls() -> None:
    legs = FakeBody(Pose(0.0, 0.0, 0.0), [(1.0, 0.1, 0.06), (1.0, -0.1, 0.06)])
    post = FakeBody(Pose(0.0, 0.0, 0.0), [(1.3, 0.0, 0.36)])  # its face is as near
    at_robot = [float(LocalGrid.from_scan(body.scan(), leg_margin=0.12).clearance_at(
        np.zeros(1), np.zeros(1))[0]) for body in (legs, post)]
    assert at_robot[1] == pytest.approx(0.94, abs=0.04)
    assert at_robot[0] < at_robot[1] - 0.08


@pytest.mark.parametrize("planner", PLANNERS)
def test_bad_requests_are_refused(planner: type[LocalController]) -> None:
    body = FakeBody(Pose(0.0, 0.0, 0.0))
    with pytest.raises(LocalPlannerError, match="path is empty"):
        planner().plan(body.pose, Twist(), body.scan(), [], body.limits, body.drive, 0.25)
    with pytest.raises(LocalPlannerError, match="radius"):
        planner().plan(body.pose, Twist(), body.scan(), [(1.0, 0.0)], body.limits, body.drive,
                       0.0)
    with pytest.raises(LocalPlannerError, match="finite"):
        planner().plan(body.pose, Twist(), body.scan(), [(math.nan, 0.0)], body.limits,
                       body.drive, 0.25)


def test_bad_planner_settings_are_refused() -> None:
    with pytest.raises(LocalPlannerError, match="step"):
        MotionSearchPlanner(step=0.0)
    with pytest.raises(LocalPlannerError, match="greed"):
        MotionSearchPlanner(greed=0.5)
    with pytest.raises(LocalPlannerError, match="horizon"):
        DynamicWindowPlanner(horizon=-1.0)
