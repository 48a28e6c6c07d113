"""Stage-1 A* (jump point search, libtcod): the contract the pure-Python A* had, and its costs."""

from __future__ import annotations

import heapq
import itertools

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from homebot.navigation import astar
from homebot.navigation.astar import cached_jump_tables, forget_jump_tables
from homebot.navigation.jump_points import jump_point_search, jump_tables


def _reference_astar(blocked: np.ndarray, shape: tuple[int, int], start: int,
                     goal: int) -> int | None:
    """The cost of the shortest path by a plain Dijkstra (1000 straight, 1414 diagonal)."""
    rows, columns = shape
    grid = blocked.reshape(shape)
    best = {start: 0}
    frontier = [(0, start)]
    while frontier:
        cost, cell = heapq.heappop(frontier)
        if cell == goal:
            return cost
        if cost > best[cell]:
            continue
        row, column = divmod(cell, columns)
        for dr, dc in itertools.product((-1, 0, 1), repeat=2):
            r, c = row + dr, column + dc
            if (dr, dc) == (0, 0) or not (0 <= r < rows and 0 <= c < columns) or grid[r, c]:
                continue
            if dr and dc and (grid[row + dr, column] or grid[row, column + dc]):
                continue
            new = cost + (1414 if dr and dc else 1000)
            if new < best.get(r * columns + c, 1 << 62):
                best[r * columns + c] = new
                heapq.heappush(frontier, (new, r * columns + c))
    return None


def _cost(path: list[int], columns: int) -> int:
    cells = [divmod(cell, columns) for cell in path]
    return sum(1414 if a[0] != b[0] and a[1] != b[1] else 1000
               for a, b in itertools.pairwise(cells))


def _check_moves(path: list[int], grid: np.ndarray) -> None:
    cells = [divmod(cell, grid.shape[1]) for cell in path]
    for (r1, c1), (r2, c2) in itertools.pairwise(cells):
        assert max(abs(r1 - r2), abs(c1 - c2)) == 1
        assert not grid[r2, c2]
        if r1 != r2 and c1 != c2:
            assert not grid[r1, c2] and not grid[r2, c1], "a diagonal cut a corner"


def test_paths_are_as_short_as_dijkstra_finds_on_random_grids() -> None:
    rng = np.random.default_rng(7)
    compared = 0
    for _ in range(150):
        rows, columns = (int(n) for n in rng.integers(3, 45, 2))
        grid = rng.random((rows, columns)) < rng.uniform(0.0, 0.45)
        free = np.flatnonzero(~grid.ravel())
        if len(free) < 2:
            continue
        start, goal = (int(cell) for cell in rng.choice(free, 2, replace=False))
        path = astar(grid.ravel(), grid.shape, start, goal)
        expected = _reference_astar(grid.ravel(), grid.shape, start, goal)
        if expected is None:
            assert path is None
            continue
        assert path is not None and path[0] == start and path[-1] == goal
        _check_moves(path, grid)
        assert _cost(path, columns) == expected
        compared += 1
    assert compared > 80


def test_a_detour_leaving_the_first_window_is_still_shortest() -> None:
    grid = np.zeros((120, 120), dtype=bool)
    grid[5:115, 60] = True  # a long wall between start and goal
    start, goal = 60 * 120 + 20, 60 * 120 + 100
    path = astar(grid.ravel(), grid.shape, start, goal)
    assert path is not None
    _check_moves(path, grid)
    assert _cost(path, 120) == _reference_astar(grid.ravel(), grid.shape, start, goal)


def test_corner_squeeze_is_not_taken() -> None:
    grid = np.zeros((3, 3), dtype=bool)
    grid[0, 1] = grid[1, 0] = True  # (0,0) and (1,1) touch only diagonally past two corners
    assert astar(grid.ravel(), grid.shape, 0, 4) is None
    grid[1, 0] = False
    path = astar(grid.ravel(), grid.shape, 0, 4)
    assert path == [0, 3, 4]


@pytest.mark.parametrize("start, goal", [(0, 99), (55, 0)])
def test_blocked_start_or_goal_gives_none(start: int, goal: int) -> None:
    grid = np.zeros((10, 10), dtype=bool)
    grid.ravel()[[99, 55]] = True
    assert astar(grid.ravel(), grid.shape, start, goal) is None


def test_start_equal_to_goal_is_a_one_cell_path() -> None:
    grid = np.zeros((5, 5), dtype=bool)
    assert astar(grid.ravel(), grid.shape, 12, 12) == [12]


@st.composite
def _grids_with_walls(draw: st.DrawFn) -> tuple[np.ndarray, int, int]:
    """A random grid with random speckle and straight walls, and two free cells in it."""
    rows = draw(st.integers(1, 24))
    columns = draw(st.integers(1, 24))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    grid = rng.random((rows, columns)) < draw(st.sampled_from([0.0, 0.05, 0.15, 0.3, 0.45]))
    for _ in range(draw(st.integers(0, 4))):
        if rng.random() < 0.5:
            row, first, last = rng.integers(rows), *sorted(rng.integers(0, columns, 2))
            grid[row, first:last + 1] = True
        else:
            column, first, last = rng.integers(columns), *sorted(rng.integers(0, rows, 2))
            grid[first:last + 1, column] = True
    free = np.flatnonzero(~grid.ravel())
    assume(len(free) >= 1)
    start, goal = (int(cell) for cell in rng.choice(free, 2, replace=True))
    return grid, start, goal


@settings(max_examples=400, derandomize=True, deadline=None)
@given(_grids_with_walls())
def test_jump_point_search_finds_dijkstras_cost_with_valid_moves(
        case: tuple[np.ndarray, int, int]) -> None:
    grid, start, goal = case
    expected = _reference_astar(grid.ravel(), grid.shape, start, goal)
    found = jump_point_search(jump_tables(grid.ravel(), grid.shape), start, goal)
    if expected is None:
        assert found is None
        return
    assert found is not None
    path, cost = found
    assert path[0] == start and path[-1] == goal
    _check_moves(path, grid)
    assert cost == _cost(path, grid.shape[1]) == expected


@settings(max_examples=100, derandomize=True, deadline=None)
@given(_grids_with_walls())
def test_astar_finds_the_same_shortest_path_with_or_without_kept_tables(
        case: tuple[np.ndarray, int, int]) -> None:
    grid, start, goal = case
    forget_jump_tables()
    fresh = astar(grid.ravel(), grid.shape, start, goal)  # windowed, or new tables
    cached_jump_tables(grid.ravel(), grid.shape)
    again = astar(grid.ravel(), grid.shape, start, goal)  # this grid's kept tables
    assert fresh == again  # what was searched before never changes the path
    expected = _reference_astar(grid.ravel(), grid.shape, start, goal)
    if expected is None:
        assert fresh is None
        return
    assert fresh is not None and fresh[0] == start and fresh[-1] == goal
    _check_moves(fresh, grid)
    assert _cost(fresh, grid.shape[1]) == expected


def test_jump_tables_and_libtcod_agree_round_a_long_wall_with_doorways() -> None:
    """An apartment-sized grid: walls with doorways, both searches, Dijkstra's cost."""
    grid = np.zeros((90, 110), dtype=bool)
    grid[0, :] = grid[-1, :] = grid[:, 0] = grid[:, -1] = True
    grid[5:85, 40] = True
    grid[44:47, 40] = False  # a doorway
    grid[30, 40:105] = True
    grid[30, 70:73] = False
    start, goal = 60 * 110 + 10, 10 * 110 + 100
    expected = _reference_astar(grid.ravel(), grid.shape, start, goal)
    jumped = jump_point_search(jump_tables(grid.ravel(), grid.shape), start, goal)
    assert jumped is not None and jumped[1] == expected
    _check_moves(jumped[0], grid)
    window = astar(grid.ravel(), grid.shape, start, 60 * 110 + 14)  # a short, easy path
    assert window is not None and _cost(window, 110) == 4000


def test_many_easy_searches_keep_the_tables_of_a_grid_in_use() -> None:
    forget_jump_tables()
    static = np.zeros((100, 120), dtype=bool)  # the window below is 1/38 of it
    static[5:95, 60] = True
    kept = cached_jump_tables(static.ravel(), static.shape)
    for obstacle in range(100):  # as plan_around's masks: a new grid each call
        grid = static.copy()
        grid.ravel()[obstacle * 7 % grid.size] = True
        assert astar(grid.ravel(), grid.shape, 2 * 120 + 2, 2 * 120 + 8) is not None
    assert cached_jump_tables(static.ravel(), static.shape) is kept
    forget_jump_tables()
    assert cached_jump_tables(static.ravel(), static.shape) is not kept
