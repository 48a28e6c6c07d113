"""A* over an 8-connected occupancy grid (CAESAR's stage 1), searched by libtcod.

The search itself runs in libtcod's C pathfinder (``tcod.path``, wheels for
CPython 3.10+ on x86_64 and aarch64): a pure-Python A* took 140–530 ms for a
15 m detour round a long wall. The cost model is the one homebot always had:
a straight step costs 1000, a diagonal one 1414 (octile distances in
thousandths of a cell, integers so that equal paths tie exactly), a diagonal
step is allowed only when both cells beside it are free (no corner cutting),
and the heuristic is the octile distance, so paths are shortest.

libtcod allocates its distance arrays over the whole grid, which costs more
than the search itself when the path is easy. So the search first runs in a
small window round start and goal, and keeps that path only when it is
provably as short as any path that leaves the window (its cost is at most
the octile lower bound through the ring of cells just outside); otherwise it
searches the whole grid. Either way the result is a shortest path.
"""

from __future__ import annotations

import numpy as np
import tcod.path

__all__ = ["astar"]

_STRAIGHT = 1000
_DIAGONAL = 1414
# Cells added round the start–goal box for the first, windowed search.
_WINDOW_MARGIN = 12
_STRAIGHT_MOVES = ((-1, 0), (1, 0), (0, -1), (0, 1))
_DIAGONAL_MOVES = ((-1, -1), (-1, 1), (1, -1), (1, 1))


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
        which one is returned is libtcod's choice.
    """
    if blocked[start] or blocked[goal]:
        return None
    rows, columns = shape
    free = ~np.asarray(blocked, dtype=bool).reshape(shape)
    start_cell, goal_cell = divmod(start, columns), divmod(goal, columns)
    top = max(min(start_cell[0], goal_cell[0]) - _WINDOW_MARGIN, 0)
    bottom = min(max(start_cell[0], goal_cell[0]) + _WINDOW_MARGIN + 1, rows)
    left = max(min(start_cell[1], goal_cell[1]) - _WINDOW_MARGIN, 0)
    right = min(max(start_cell[1], goal_cell[1]) + _WINDOW_MARGIN + 1, columns)
    whole = top == 0 and left == 0 and bottom == rows and right == columns
    if not whole:
        found = _search(free[top:bottom, left:right], (start_cell[0] - top, start_cell[1] - left),
                        (goal_cell[0] - top, goal_cell[1] - left))
        if found is not None:
            cells, cost = found
            if cost <= _exit_bound(shape, (top, bottom, left, right), start_cell, goal_cell):
                return [(row + top) * columns + column + left for row, column in cells]
    found = _search(free, start_cell, goal_cell)
    if found is None:
        return None
    return [row * columns + column for row, column in found[0]]


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
