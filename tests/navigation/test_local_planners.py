"""Stage 2 (A* over motion commands) and the DWA baseline on a fake body with a ray-cast laser."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from fake_body import FakeBody, wall

from homebot.errors import LocalPlannerError
from homebot.geometry import Pose
from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localmap import LocalController, LocalGrid
from homebot.robot import DriveKind, Twist

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
    # with neither the cost on changing it nor the hysteresis between cycles. (Between the
    # first post and the wall there is 0.75 m, room for the robot and its margins.)
    path = [(0.0, 0.0), (2.0, 0.6), (5.0, 0.0)]
    obstacles = [(1.5, 0.3, 0.2), (2.8, -0.4, 0.2), *wall(0.0, 1.3, 5.0, 1.3)]
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


def test_a_leg_half_hidden_behind_the_other_is_a_leg_too() -> None:
    # Seen from the side in front of a wall (a doorway's jamb): the far leg shows only
    # beside the near one. Both count the leg margin nearer, the wall does not.
    body = FakeBody(Pose(0.0, 0.0, 0.0), [(0.6, 0.0, 0.06), (0.75, -0.12, 0.06),
                                         *wall(1.1, -1.0, 1.1, 1.0)])
    grid = LocalGrid.from_scan(body.scan(), leg_margin=0.12)
    near_legs = np.hypot(grid.returns[:, 0] - 0.68, grid.returns[:, 1] + 0.06) < 0.2
    assert near_legs.sum() > 5
    assert np.all(grid.returns[near_legs, 2] == 0.12)
    assert np.all(grid.returns[~near_legs, 2] == 0.0)
    assert np.all(grid.returns[near_legs, 3] == 0.0)  # not walls
    assert np.all(grid.returns[~near_legs, 3] == 1.0)
    assert grid.exact_clearance(0.0, 0.0) == pytest.approx(0.54 - 0.12, abs=0.005)


def test_exact_clearance_is_the_distance_to_the_nearest_return() -> None:
    # The bucketed look-up in the search is exact below its bound, wherever in a cell.
    pytest.importorskip("numba")
    from homebot.navigation import motion_search

    body = FakeBody(Pose(0.0, 0.0, 0.4), [(0.8, 0.3, 0.2), (0.5, -0.55, 0.06),
                                         (0.6, -0.75, 0.06), *wall(-1.0, 1.2, 2.0, 1.2)])
    grid = LocalGrid.from_scan(body.scan(), leg_margin=0.12)
    rng = np.random.default_rng(3)
    for x, y in rng.uniform(-1.5, 1.5, (300, 2)):
        for farther in (0.0, 0.02):
            exact = grid.exact_clearance(x, y, farther)
            for bound in (0.2, 0.45, 3.0):
                near = motion_search.clearance_near(grid.returns, grid.starts, grid.per_side,
                                                    grid.bucket, grid.half_size, x, y, bound,
                                                    grid.leg_margin, farther)
                assert near == pytest.approx(min(exact, bound))
        exact = grid.exact_clearance(x, y)
        # A cell's clearance overstates it by no more than the grid's slack, and understates
        # it by no more than a third of that (what the search relies on).
        cell = float(grid.clearance_at(np.array([x]), np.array([y]))[0])
        assert exact - grid.slack / 3 - 1e-9 <= cell <= max(exact, 0.0) + grid.slack


def test_local_grid_clearance_is_an_exact_distance_transform() -> None:
    # Each cell's clearance is the distance from its centre to the return kept (the last
    # to fall) in one of its nearest occupied cells, nearest by an exact Euclidean distance.
    pytest.importorskip("numba")
    from homebot.navigation import motion_search

    rng = np.random.default_rng(5)
    cells, resolution = 41, 0.05
    half = cells * resolution / 2
    centres = (np.arange(cells) + 0.5) * resolution - half
    for count in (1, 7, 60, 400):
        points = rng.uniform(-1.2 * half, 1.2 * half, (count, 2))
        clearance = motion_search.clearance_grid(points, cells, half, resolution, 10.0)
        columns = np.floor((points[:, 0] + half) / resolution).astype(int)
        rows = np.floor((points[:, 1] + half) / resolution).astype(int)
        inside = (columns >= 0) & (columns < cells) & (rows >= 0) & (rows < cells)
        kept: dict[tuple[int, int], np.ndarray] = {}
        for row, column, point in zip(rows[inside], columns[inside], points[inside],
                                      strict=True):
            kept[int(row), int(column)] = point
        if not kept:
            assert np.all(clearance == 10.0)
            continue
        occupied = np.array(list(kept))
        returns = np.array(list(kept.values()))
        for row, column in itertools.product(range(cells), range(cells)):
            gaps = np.hypot(occupied[:, 0] - row, occupied[:, 1] - column)
            nearest = np.isclose(gaps, gaps.min())
            candidates = np.hypot(returns[nearest, 0] - centres[column],
                                  returns[nearest, 1] - centres[row])
            assert np.isclose(candidates, clearance[row, column]).any()


def test_cells_the_local_search_cannot_reach_lead_to_the_nearest_it_can() -> None:
    # An unreached cell gets the field of its nearest reached cell plus the way there.
    pytest.importorskip("numba")
    from homebot.navigation import motion_search

    rng = np.random.default_rng(8)
    field = np.where(rng.random((23, 23)) < 0.3, rng.uniform(0.0, 5.0, (23, 23)), np.inf)
    filled = motion_search.fill_unreached(field, 0.1)
    reached = np.argwhere(np.isfinite(field))
    for row, column in itertools.product(range(23), range(23)):
        gaps = np.hypot(reached[:, 0] - row, reached[:, 1] - column)
        nearest = reached[np.isclose(gaps, gaps.min())]
        assert np.isclose(filled[row, column],
                          field[nearest[:, 0], nearest[:, 1]] + 0.1 * gaps.min()).any()
    assert np.all(np.isinf(motion_search.fill_unreached(np.full((5, 5), np.inf), 0.1)))


@pytest.mark.parametrize(("start", "goal"), [((0.0, 0.0), (3.0, 0.37)),
                                             ((0.66, 0.0), (3.0, 0.0))])
@pytest.mark.parametrize("allowance", [0.0, 0.02])
def test_stage2_keeps_its_margin_exactly_at_a_wall_it_cannot_pass(
        start: tuple[float, float], goal: tuple[float, float], allowance: float) -> None:
    # The goal lies beyond a wall: the robot comes up to it and stays there, its margin
    # kept to the millimetre (the grid's 5 cm cells once let it creep 1.6 cm into it),
    # less what it may crawl nearer walls.
    body = FakeBody(Pose(*start, 0.0), wall(1.0, -2.0, 1.0, 2.0, spacing=0.03, radius=0.02))
    planner = MotionSearchPlanner(crawl_allowance=allowance)
    assert not _drive(body, planner, [start, goal], seconds=20.0)
    assert body.collisions == 0
    assert body.min_clearance >= body.radius + planner.safety - allowance - 0.001


@pytest.mark.parametrize("goal_y", [0.0, 0.2])
def test_stage2_crawls_up_to_nothing_narrow_inside_its_margin(goal_y: float) -> None:
    # A lone post as thin as a leg (an unpaired one) stands before a wall, on the way to a
    # goal beyond both: the robot stops at its full margin from the post, not crawling
    # the allowance nearer as it may to walls (counting the post as a wall, 0.28 m).
    post = (0.9, 0.0, 0.06)
    body = FakeBody(Pose(0.0, 0.0, 0.0), [post, *wall(1.3, -2.0, 1.3, 2.0, spacing=0.03,
                                                       radius=0.02)])
    planner = MotionSearchPlanner()
    assert not _drive(body, planner, [(0.0, 0.0), (3.0, goal_y)], seconds=20.0)
    assert body.collisions == 0
    assert body.min_clearance == pytest.approx(math.dist(body.pose.xy(), post[:2]) - post[2])
    assert body.min_clearance >= body.radius + planner.safety - 0.001


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
