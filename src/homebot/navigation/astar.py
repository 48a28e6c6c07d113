"""A* over an 8-connected occupancy grid (CAESAR's stage 1), by jump point search.

The cost model is the one homebot always had: a straight step costs 1000, a
diagonal one 1414 (octile distances in thousandths of a cell, integers so that
equal paths tie exactly), a diagonal step is allowed only when both cells
beside it are free (no corner cutting), and the heuristic is the octile
distance, so paths are shortest.

The search is jump point search over precomputed tables of the straight jumps
(``jump_points``): a few tenths of a millisecond for a 15 m path, where a
cell-by-cell A* round a long wall settles tens of thousands of cells.

A search whose start and goal lie close (their box, with a margin, covers at
most a thirty-second of the grid) first runs in that window, with tables of the
window only (a fraction of a millisecond), and keeps that path when it is
provably as short as any path that leaves the window (its cost is at most the
octile lower bound through the ring of cells just outside). Otherwise it
searches the whole grid, whose tables take about a millisecond to build for
the apartment's grid and a few for a 400 x 400 one; they are kept per grid
(keyed by the mask's bits, the last few grids), so a grid searched again, as
the Navigator's static masks are, pays them once, while ``plan_around``'s new
mask per call pays them unless its window proves the path. Which search runs
depends on the grid, start and goal alone, and kept tables equal new ones, so
the path found never depends on what was searched before.

``libtcod_astar`` is the same search by libtcod's C A* (``tcod.path``), which
stage 1 used before, kept to compare with: ``homebot bench navigation``
reports both, and the tables' build time apart.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable

import numpy as np
import tcod.path

from homebot.navigation.jump_points import JumpTables, jump_point_search, jump_tables

__all__ = ["astar", "cached_jump_tables", "forget_jump_tables", "libtcod_astar"]

_STRAIGHT = 1000
_DIAGONAL = 1414
# Cells added round the start–goal box for the first, windowed search.
_WINDOW_MARGIN = 12
# A window larger than this share of the grid is not tried: on the apartment's
# static masks (kept tables) windows of an eighth made Navigator.plan 3.5 times
# slower; a new grid (plan_around) pays the whole grid's tables instead.
_LARGEST_WINDOW = 1 / 32
_STRAIGHT_MOVES = ((-1, 0), (1, 0), (0, -1), (0, 1))
_DIAGONAL_MOVES = ((-1, -1), (-1, 1), (1, -1), (1, 1))
# Grids whose jump tables are kept (up to a few megabytes each).
_KEPT_TABLES = 8
_Key = tuple[tuple[int, int], bytes]


class _TableCache:
    """Jump tables of the grids searched lately, keyed by shape and mask bits."""

    def __init__(self) -> None:
        self.tables: OrderedDict[_Key, JumpTables] = OrderedDict()

    def get(self, key: _Key) -> JumpTables | None:
        """A grid's kept tables (now the latest used), or None."""
        tables = self.tables.pop(key, None)
        if tables is not None:
            self.tables[key] = tables
        return tables

    def store(self, key: _Key, tables: JumpTables) -> None:
        """Keep a grid's tables, dropping those used longest ago beyond the limit."""
        self.tables[key] = tables
        while len(self.tables) > _KEPT_TABLES:
            try:
                self.tables.popitem(last=False)
            except KeyError:  # emptied meanwhile
                return

    def clear(self) -> None:
        """Forget every grid."""
        self.tables.clear()


# Memoisation only: what astar returns does not depend on it.
_CACHE = _TableCache()


def cached_jump_tables(blocked: np.ndarray, shape: tuple[int, int]) -> JumpTables:
    """The jump tables of a grid, built now unless kept from an earlier search.

    Args:
        blocked: flat boolean mask, True where the robot cannot be.
        shape: (rows, columns) of the grid.

    Returns:
        The grid's tables, now kept for later ``astar`` calls on it.
    """
    mask = np.ascontiguousarray(blocked, dtype=bool)
    key = ((int(shape[0]), int(shape[1])), np.packbits(mask).tobytes())
    tables = _CACHE.get(key)
    if tables is None:
        tables = jump_tables(mask, shape)
        _CACHE.store(key, tables)
    return tables


def astar(blocked: np.ndarray, shape: tuple[int, int], start: int, goal: int) -> list[int] | None:
    """Cheapest path of flat cell indices from ``start`` to ``goal``, or None.

    Args:
        blocked: flat boolean mask, True where the robot cannot be.
        shape: (rows, columns) of the grid.
        start: flat index of the start cell (must be free).
        goal: flat index of the goal cell (must be free).

    Returns:
        The cells from start to goal inclusive; None when the goal is unreachable.
        Diagonal moves never cut a blocked corner. Among equally short paths,
        which one is returned is the search's choice.
    """
    if blocked[start] or blocked[goal]:
        return None
    mask = np.ascontiguousarray(blocked, dtype=bool)
    found = _windowed(mask, shape, start, goal, _jump_search, _LARGEST_WINDOW)
    if found is not None:
        return found
    searched = jump_point_search(cached_jump_tables(mask, shape), start, goal)
    return None if searched is None else searched[0]


def libtcod_astar(blocked: np.ndarray, shape: tuple[int, int], start: int,
                  goal: int) -> list[int] | None:
    """The same search by libtcod's A* alone (windowed, then the whole grid), to compare with.

    Args:
        blocked: flat boolean mask, True where the robot cannot be.
        shape: (rows, columns) of the grid.
        start: flat index of the start cell.
        goal: flat index of the goal cell.

    Returns:
        As ``astar``.
    """
    if blocked[start] or blocked[goal]:
        return None
    mask = np.ascontiguousarray(blocked, dtype=bool)
    found = _windowed(mask, shape, start, goal, _search)
    if found is not None:
        return found
    searched = _search(~mask.reshape(shape), divmod(start, shape[1]), divmod(goal, shape[1]))
    return None if searched is None else [row * shape[1] + column for row, column in searched[0]]


def forget_jump_tables() -> None:
    """Drop every kept grid, so that the next search of any grid is a first one."""
    _CACHE.clear()


_Search = Callable[[np.ndarray, tuple[int, int], tuple[int, int]],
                   "tuple[list[tuple[int, int]], int] | None"]


def _windowed(mask: np.ndarray, shape: tuple[int, int], start: int, goal: int,
              search: _Search, largest: float = 1.0) -> list[int] | None:
    """The path ``search`` finds in a window round start and goal, if provably shortest.

    None also when the window would cover more than ``largest`` of the grid.
    """
    rows, columns = shape
    start_cell, goal_cell = divmod(start, columns), divmod(goal, columns)
    top = max(min(start_cell[0], goal_cell[0]) - _WINDOW_MARGIN, 0)
    bottom = min(max(start_cell[0], goal_cell[0]) + _WINDOW_MARGIN + 1, rows)
    left = max(min(start_cell[1], goal_cell[1]) - _WINDOW_MARGIN, 0)
    right = min(max(start_cell[1], goal_cell[1]) + _WINDOW_MARGIN + 1, columns)
    if (bottom - top) * (right - left) > largest * rows * columns or (
            top == 0 and left == 0 and bottom == rows and right == columns):
        return None
    free = ~mask.reshape(shape)[top:bottom, left:right]
    found = search(free, (start_cell[0] - top, start_cell[1] - left),
                   (goal_cell[0] - top, goal_cell[1] - left))
    if found is None:
        return None
    cells, cost = found
    if cost > _exit_bound(shape, (top, bottom, left, right), start_cell, goal_cell):
        return None
    return [(row + top) * columns + column + left for row, column in cells]


def _octile(rows: np.ndarray, columns: np.ndarray, cell: tuple[int, int]) -> np.ndarray:
    dr, dc = np.abs(rows - cell[0]), np.abs(columns - cell[1])
    result: np.ndarray = _STRAIGHT * (dr + dc) + (_DIAGONAL - 2 * _STRAIGHT) * np.minimum(dr, dc)
    return result


def _exit_bound(shape: tuple[int, int], window: tuple[int, int, int, int],
                start: tuple[int, int], goal: tuple[int, int]) -> float:
    """A lower bound on the cost of any path that leaves the window."""
    top, bottom, left, right = window
    rows, columns = shape
    ring_rows: list[np.ndarray] = []
    ring_columns: list[np.ndarray] = []
    span_columns = np.arange(max(left - 1, 0), min(right + 1, columns))
    span_rows = np.arange(max(top - 1, 0), min(bottom + 1, rows))
    for row, present in ((top - 1, top > 0), (bottom, bottom < rows)):
        if present:
            ring_rows.append(np.full(len(span_columns), row))
            ring_columns.append(span_columns)
    for column, present in ((left - 1, left > 0), (right, right < columns)):
        if present:
            ring_rows.append(span_rows)
            ring_columns.append(np.full(len(span_rows), column))
    if not ring_rows:
        return float("inf")
    ring_r, ring_c = np.concatenate(ring_rows), np.concatenate(ring_columns)
    return float(np.min(_octile(ring_r, ring_c, start) + _octile(ring_r, ring_c, goal)))


def _jump_search(free: np.ndarray, start: tuple[int, int],
                 goal: tuple[int, int]) -> tuple[list[tuple[int, int]], int] | None:
    """Jump point search on the boolean ``free`` grid (new tables): cells and cost, or None."""
    columns = free.shape[1]
    tables = jump_tables(~free.ravel(), free.shape)
    found = jump_point_search(tables, start[0] * columns + start[1], goal[0] * columns + goal[1])
    if found is None:
        return None
    return [divmod(cell, columns) for cell in found[0]], found[1]


def _search(free: np.ndarray, start: tuple[int, int],
            goal: tuple[int, int]) -> tuple[list[tuple[int, int]], int] | None:
    """libtcod A* on the boolean ``free`` grid: the cells and the path's cost, or None."""
    free = np.ascontiguousarray(free)
    rows, columns = free.shape
    cost = free.view(np.int8)
    graph = tcod.path.CustomGraph((rows, columns))
    for move in _STRAIGHT_MOVES:
        graph.add_edge(move, _STRAIGHT, cost=cost)
    padded = np.zeros((rows + 2, columns + 2), dtype=bool)
    padded[1:-1, 1:-1] = free
    for dr, dc in _DIAGONAL_MOVES:
        # A diagonal step from a cell needs both its side cells free.
        beside = padded[1 + dr:1 + dr + rows, 1:-1] & padded[1:-1, 1 + dc:1 + dc + columns]
        graph.add_edge((dr, dc), _DIAGONAL, cost=cost, condition=beside.view(np.int8))
    graph.set_heuristic(cardinal=_STRAIGHT, diagonal=_DIAGONAL)
    finder = tcod.path.Pathfinder(graph)
    finder.add_root(start)
    path = finder.path_to(goal)
    reached = int(finder.distance[goal])
    if reached == np.iinfo(finder.distance.dtype).max:
        return None
    return [(int(row), int(column)) for row, column in path], reached
