"""A* over an 8-connected occupancy grid, with the octile distance as heuristic.

Hand-written rather than taken from a library because the grid is small, the
search must stop at the goal (scipy's csgraph computes whole distance fields)
and a tight pure-Python loop meets the ≤ 5 ms budget for a 15 m path.
"""

from __future__ import annotations

import heapq

import numpy as np

__all__ = ["astar"]

# Integer step costs (thousandths of a cell) so that equally good paths tie exactly.
_STRAIGHT = 1000
_DIAGONAL = 1414
_DIAGONAL_SAVING = _DIAGONAL - 2 * _STRAIGHT
_UNREACHED = 1 << 62


def astar(blocked: np.ndarray, shape: tuple[int, int], start: int, goal: int) -> list[int] | None:
    """Cheapest path of flat cell indices from ``start`` to ``goal``, or None.

    Args:
        blocked: flat boolean mask, True where the robot cannot be.
        shape: (rows, columns) of the grid.
        start: flat index of the start cell (must be free).
        goal: flat index of the goal cell (must be free).

    Returns:
        The cells from start to goal inclusive; None when the goal is unreachable.
        Diagonal moves never cut a blocked corner.
    """
    if blocked[start] or blocked[goal]:
        return None
    rows, columns = shape
    size = rows * columns
    closed = bytearray(blocked.tobytes())  # 1 = blocked or expanded
    g_score = [_UNREACHED] * size
    parent = [-1] * size
    goal_row, goal_column = divmod(goal, columns)
    straight = (-columns, columns, -1, 1)
    diagonal = ((-columns - 1, -columns, -1), (-columns + 1, -columns, 1),
                (columns - 1, columns, -1), (columns + 1, columns, 1))

    def heuristic(cell: int) -> int:
        row, column = divmod(cell, columns)
        dr, dc = abs(row - goal_row), abs(column - goal_column)
        return _STRAIGHT * (dr + dc) + (_DIAGONAL - 2 * _STRAIGHT) * (dr if dr < dc else dc)

    moves = [(offset, _STRAIGHT, 0, 0, offset) for offset in straight]
    moves += [(offset, _DIAGONAL, vertical, horizontal, horizontal)
              for offset, vertical, horizontal in diagonal]
    g_score[start] = 0
    # Ties on f are broken towards the larger g (deeper nodes): on open floor this
    # follows one straight line instead of expanding every equally good cell.
    frontier = [(heuristic(start), 0, start)]
    push, pop = heapq.heappush, heapq.heappop
    while frontier:
        _, negative_cost, cell = pop(frontier)
        if closed[cell] == 2:
            continue
        if cell == goal:
            return _walk_back(parent, goal)
        closed[cell] = 2
        cost = -negative_cost
        column = cell % columns
        at_left, at_right = column == 0, column == columns - 1
        for offset, step, vertical, horizontal, sideways in moves:
            if (sideways == 1 and at_right) or (sideways == -1 and at_left):
                continue
            neighbour = cell + offset
            if neighbour < 0 or neighbour >= size or closed[neighbour]:
                continue
            if vertical and (closed[cell + vertical] == 1 or closed[cell + horizontal] == 1):
                continue  # a diagonal move would cut the corner of an obstacle
            new_cost = cost + step
            if new_cost < g_score[neighbour]:
                g_score[neighbour] = new_cost
                parent[neighbour] = cell
                row, col = divmod(neighbour, columns)
                dr = row - goal_row if row > goal_row else goal_row - row
                dc = col - goal_column if col > goal_column else goal_column - col
                estimate = _STRAIGHT * (dr + dc) + _DIAGONAL_SAVING * (dr if dr < dc else dc)
                push(frontier, (new_cost + estimate, -new_cost, neighbour))
    return None


def _walk_back(parent: list[int], goal: int) -> list[int]:
    path = [goal]
    while parent[path[-1]] != -1:
        path.append(parent[path[-1]])
    path.reverse()
    return path
