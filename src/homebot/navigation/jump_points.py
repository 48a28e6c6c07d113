"""Jump point search on an 8-connected grid without corner cutting.

Harabor and Grastien's jump point search, in the variant that forbids corner
cutting (a diagonal step needs both cells beside it free; "Improving Jump
Point Search", ICAPS 2014), with the straight jumps precomputed as in Rabin's
JPS+: for each free cell and each of the four straight directions, how many
steps lead to the next jump point or, when none comes first, how many are free
before a wall. numpy builds these tables in a few whole-grid passes (a running
minimum or maximum along each row or column). A straight jump is then one
lookup; a diagonal jump walks its cells in Python, two lookups per cell. Only
jump points are expanded: a few dozen on open floor or round a long wall,
where a cell-by-cell A* settles tens of thousands of cells. (Tables for the
diagonal jumps too, full JPS+, made the search faster still but doubled the
tables' build time, which a grid searched only once pays in full.)

The rules, for a step in direction ``d`` arriving at cell ``x``:

* straight ``d``: ``x`` is a jump point when a cell ``x + s`` beside it is free
  while ``x + s - d`` is blocked (the diagonal to ``x + s`` was unavailable).
  Its successors are ``d``, and ``s`` and ``d + s`` for each such side.
* diagonal ``d = (dr, dc)``: no forced neighbours. ``x`` is a jump point when a
  straight jump from it along ``(dr, 0)`` or ``(0, dc)`` finds one. Its
  successors are ``(dr, 0)``, ``(0, dc)`` and ``d``.

The goal is found by "goal bounding": a straight jump whose line holds the
goal within its free run stops there; a diagonal jump stops at the first cell
from which a straight run reaches the goal. Costs are the integers of
``homebot.navigation.astar`` (1000 straight, 1414 diagonal), the heuristic the
octile distance, so the paths are shortest; property tests compare them with
Dijkstra's.
"""

from __future__ import annotations

import heapq
import itertools
from dataclasses import dataclass

import numpy as np

__all__ = ["JumpTables", "jump_point_search", "jump_tables"]

_STRAIGHT = 1000
_DIAGONAL = 1414
# Directions as (row step, column step); the first four index JumpTables.jumps.
_DIRECTIONS = ((0, 1), (0, -1), (1, 0), (-1, 0), (1, 1), (1, -1), (-1, 1), (-1, -1))
_INDEX = {direction: index for index, direction in enumerate(_DIRECTIONS)}


@dataclass(frozen=True)
class JumpTables:
    """Precomputed jumps of one grid, padded by a blocked border one cell wide.

    ``jumps[i][p]`` codes, for the free padded flat cell ``p`` and straight
    direction ``_DIRECTIONS[i]`` (i < 4), what a jump finds: ``2 k`` when the
    next jump point is k steps away, ``2 k + 1`` when a wall comes first, after
    k - 1 free steps. ``free[p]`` is 1 for a free cell. ``arrays`` keeps the
    numpy buffers these views read.
    """

    shape: tuple[int, int]
    width: int
    free: memoryview
    jumps: tuple[memoryview, ...]
    arrays: tuple[np.ndarray, ...]


def jump_tables(blocked: np.ndarray, shape: tuple[int, int]) -> JumpTables:
    """Build the jump tables of a grid.

    Args:
        blocked: flat boolean mask, True where the robot cannot be.
        shape: (rows, columns) of the grid.

    Returns:
        The tables for ``jump_point_search``.
    """
    rows, columns = shape
    width = columns + 2
    padded = np.zeros((rows + 2, width), dtype=bool)
    padded[1:-1, 1:-1] = ~np.asarray(blocked, dtype=bool).reshape(shape)
    free = padded.ravel()
    size = free.size
    margin = width + 1
    extended = np.zeros(size + 2 * margin, dtype=bool)
    extended[margin:margin + size] = free

    def shifted(offset: int) -> np.ndarray:
        """``free[p + offset]`` for every p (blocked beyond the array)."""
        return extended[margin + offset:margin + offset + size]

    offsets = [dr * width + dc for dr, dc in _DIRECTIONS]
    tables: list[np.ndarray] = [np.empty(0, dtype=np.int32)] * 4
    for index in range(4):
        step = offsets[index]
        sides = (width, -width) if abs(step) == 1 else (1, -1)
        forced = np.zeros(size, dtype=bool)
        for side in sides:
            forced |= shifted(side) & ~shifted(side - step)
        tables[index] = _runs(~free, forced & free, step, width)
    free_bytes = free.view(np.uint8)
    return JumpTables(shape=(rows, columns), width=width, free=free_bytes.data,
                      jumps=tuple(table.data for table in tables),
                      arrays=(free_bytes, *tables))


def _runs(wall: np.ndarray, stop: np.ndarray, step: int, width: int) -> np.ndarray:
    """Code, for each cell p, the first k >= 1 with an event at q = p + k * step.

    An event is ``wall[q]`` (the run ends before q: k - 1 free steps) or
    ``stop[q]`` (a jump point k steps away); a wall wins over a stop. The code
    is ``2 k`` for a jump point and ``2 k + 1`` for a wall. Codes of cells whose
    run leaves the array (only blocked cells') are meaningless.

    Folded into rows of ``|step|`` cells (rows of the grid for a sideways step),
    the chains p, p + step, ... are the columns (the rows). An event is coded
    as twice its place along the chain, one more (less) for a wall, so one
    running minimum (maximum) finds the nearest event and its kind at once.
    """
    size = wall.size
    stride = abs(step)
    if stride == 1:
        places, count = width, size // width
    else:
        places = -(-size // stride)
        count = stride
    length = places * count
    dtype = np.int16 if 2 * places + 4 < np.iinfo(np.int16).max else np.int32
    walls = np.ones(length, dtype=bool)
    walls[:size] = wall
    events = walls.copy()
    events[:size] |= stop
    # Chains run along ``axis`` of the folded grid; ``at(i)`` indexes along it.
    axis = 1 if stride == 1 else 0
    shape = (count, places) if axis else (places, count)

    def at(index: int | slice) -> tuple[int | slice, ...]:
        return (slice(None), index) if axis else (index,)

    twice = 2 * np.arange(places, dtype=dtype).reshape((1, -1) if axis else (-1, 1))
    missing = dtype(2 * places + 2 if step > 0 else -2)
    code: np.ndarray = np.where(events.reshape(shape), twice, missing).astype(dtype, copy=False)
    nearest = np.empty_like(code)
    if step > 0:
        np.add(code, walls.reshape(shape), out=code)
        nearest[at(-1)] = missing
        nearest[at(slice(None, -1))] = np.minimum.accumulate(
            code[at(slice(None, 0, -1))], axis=axis)[at(slice(None, None, -1))]
        np.subtract(nearest, twice, out=nearest)
    else:
        np.subtract(code, walls.reshape(shape), out=code)
        nearest[at(0)] = missing
        nearest[at(slice(1, None))] = np.maximum.accumulate(code[at(slice(None, -1))], axis=axis)
        np.subtract(twice, nearest, out=nearest)
    result: np.ndarray = nearest.ravel()[:size]
    return result


def jump_point_search(tables: JumpTables, start: int, goal: int) -> tuple[list[int], int] | None:
    """Shortest path between two free cells (flat indices of the unpadded grid).

    Args:
        tables: the grid's jump tables (``jump_tables``).
        start: flat index of the start cell.
        goal: flat index of the goal cell.

    Returns:
        The cells from start to goal inclusive and the path's cost, or None when
        the goal is unreachable or either end is blocked.
    """
    columns = tables.shape[1]
    width = tables.width
    free = tables.free
    jumps = tables.jumps
    origin = _pad(start, columns, width)
    target = _pad(goal, columns, width)
    if not free[origin] or not free[target]:
        return None
    goal_row, goal_column = divmod(target, width)
    best = {origin: 0}
    parent = {origin: -1}
    arrived: dict[int, int] = {origin: -1}
    frontier = [(_octile(origin, target, width), 0, origin)]
    while frontier:
        _, cost, node = heapq.heappop(frontier)
        if node == target:
            return _unfold(parent, target, columns, width), cost
        if cost > best[node]:
            continue
        row, column = divmod(node, width)
        for index in _successors(arrived[node], node, free, width):
            dr, dc = _DIRECTIONS[index]
            if dr and dc:
                steps = _diagonal_steps(tables, node, index, target)
                step_cost = _DIAGONAL
            else:
                code = jumps[index][node]
                limit = (code >> 1) - (code & 1)  # free steps this way
                ahead = (goal_column - column) * dc if dr == 0 else (goal_row - row) * dr
                on_line = goal_row == row if dr == 0 else goal_column == column
                goal_ahead = on_line and 0 < ahead <= limit
                steps = ahead if goal_ahead else (code >> 1) * (1 - (code & 1))
                step_cost = _STRAIGHT
            if steps == 0:
                continue
            successor = node + steps * (dr * width + dc)
            new_cost = cost + steps * step_cost
            if new_cost < best.get(successor, new_cost + 1):
                best[successor] = new_cost
                parent[successor] = node
                arrived[successor] = index
                heapq.heappush(frontier,
                               (new_cost + _octile(successor, target, width), new_cost, successor))
    return None


def _successors(arrived: int, node: int, free: memoryview, width: int) -> list[int]:
    """Directions to jump in from ``node``, reached by a step of direction ``arrived``."""
    if arrived < 0:
        return list(range(8))
    dr, dc = _DIRECTIONS[arrived]
    if dr and dc:
        return [_INDEX[(dr, 0)], _INDEX[(0, dc)], arrived]
    result = [arrived]
    step = dr * width + dc
    for sr, sc in (((1, 0), (-1, 0)) if dr == 0 else ((0, 1), (0, -1))):
        side = sr * width + sc
        if free[node + side] and not free[node + side - step]:
            result.append(_INDEX[(sr, sc)])
            result.append(_INDEX[(dr + sr, dc + sc)])
    return result


def _diagonal_steps(tables: JumpTables, node: int, index: int, target: int) -> int:
    """Steps of a diagonal jump from ``node`` (0: none).

    It stops at the goal, at a cell from which a straight jump along either of
    its components finds a jump point, or at one from which such a straight run
    reaches the goal; it fails at a step that a wall or a corner forbids.
    """
    width, free = tables.width, tables.free
    dr, dc = _DIRECTIONS[index]
    vertical, horizontal = tables.jumps[_INDEX[(dr, 0)]], tables.jumps[_INDEX[(0, dc)]]
    up, side, step = dr * width, dc, dr * width + dc
    row, column = divmod(node, width)
    goal_row, goal_column = divmod(target, width)
    cell, steps = node, 0
    while free[cell + up] and free[cell + side] and free[cell + step]:
        cell += step
        steps += 1
        row += dr
        column += dc
        across, along = horizontal[cell], vertical[cell]
        if cell == target or not across & 1 or not along & 1:
            return steps
        if row == goal_row and 0 < (goal_column - column) * dc <= (across >> 1) - 1:
            return steps
        if column == goal_column and 0 < (goal_row - row) * dr <= (along >> 1) - 1:
            return steps
    return 0


def _octile(cell: int, other: int, width: int) -> int:
    row, column = divmod(cell, width)
    other_row, other_column = divmod(other, width)
    dr, dc = abs(row - other_row), abs(column - other_column)
    return _STRAIGHT * (dr + dc) + (_DIAGONAL - 2 * _STRAIGHT) * min(dr, dc)


def _pad(cell: int, columns: int, width: int) -> int:
    row, column = divmod(cell, columns)
    return (row + 1) * width + column + 1


def _unfold(parent: dict[int, int], target: int, columns: int, width: int) -> list[int]:
    """The cells of the path whose jump points ``parent`` links, unpadded."""
    points = [target]
    while parent[points[-1]] >= 0:
        points.append(parent[points[-1]])
    points.reverse()
    cells = [points[0]]
    for here, there in itertools.pairwise(points):
        row, column = divmod(here, width)
        there_row, there_column = divmod(there, width)
        dr = (there_row > row) - (there_row < row)
        dc = (there_column > column) - (there_column < column)
        step = dr * width + dc
        cells.extend(range(here + step, there + step, step))
    return [(cell // width - 1) * columns + cell % width - 1 for cell in cells]
