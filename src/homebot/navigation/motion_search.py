"""Stage 2's search by time as one compiled kernel (numba), see ``local_planner``.

``search`` is the whole of one cycle's A* over motion sequences: the rollout of
each motion in substeps, the collision check against the local grid's
clearance (grown by the speed), the heuristic (time to go) and the open list
(a binary heap on arrays). It is written as plain Python over scalars and
arrays (see ``homebot.compiled``), so tests can run the very same
code as ``search.py_func``. ``coarse_field`` (with ``sweep``, one Dijkstra) is
the search by length before it, ``expand`` puts its result back on the local
grid, ``clearance_grid`` builds that grid's clearance from a scan's returns,
``classify_returns`` tells legs and walls among them and ``bucketed`` sorts them for
``clearance_near``. This module is imported when a
local controller first plans.
"""

from __future__ import annotations

import math

import numpy as np

from homebot.compiled import compiled as _compiled

__all__ = ["bucketed", "classify_returns", "clearance_near", "downhill_at", "search", "sweep"]


# ------------------------------------------------------------------ helpers


@_compiled
def _sign(value: float) -> float:
    if value > 0.0:
        return 1.0
    if value < 0.0:
        return -1.0
    return 0.0


@_compiled
def _length(dx: float, dy: float) -> float:
    """sqrt(dx² + dy²): ``math.hypot`` guards against overflow, at many times the cost."""
    return math.sqrt(dx * dx + dy * dy)


@_compiled
def _ramp_time(distance: float, speed: float, top: float, acceleration: float) -> float:
    """Least time to cover ``distance`` from ``speed`` (may be negative) within ``top``."""
    speed = min(speed, top)
    ramp_distance = (top * top - _sign(speed) * speed * speed) / (2.0 * acceleration)
    if distance <= ramp_distance:
        return (-speed + math.sqrt(max(speed * speed + 2.0 * acceleration * distance, 0.0))) / \
            acceleration
    return (top - speed) / acceleration + (distance - ramp_distance) / top


@_compiled
def _rest_to_rest(angle: float, top: float, acceleration: float) -> float:
    """Least time to turn by ``angle`` from rest to rest."""
    if angle <= top * top / acceleration:
        return 2.0 * math.sqrt(max(angle, 0.0) / acceleration)
    return top / acceleration + angle / top


@_compiled
def _turn_time(angle: float, rate: float, top: float, acceleration: float) -> float:
    """Least time to turn by ``angle`` (≥ 0) and stop there, turning at ``rate`` towards it now.

    Bang-bang: speed up (to ``top`` at most), slow down; when the turn already
    under way cannot stop in time, stop past the heading and come back.
    """
    if rate < 0.0:
        away = -rate
        return away / acceleration + _rest_to_rest(angle + away * away / (2.0 * acceleration),
                                                   top, acceleration)
    toward = rate
    stopping = toward * toward / (2.0 * acceleration)
    if stopping > angle:
        return toward / acceleration + _rest_to_rest(stopping - angle, top, acceleration)
    peak = math.sqrt(acceleration * angle + toward * toward / 2.0)
    if peak <= top:
        return (2.0 * peak - toward) / acceleration
    return (top - toward) / acceleration + top / acceleration + \
        (angle - (top * top - toward * toward) / (2.0 * acceleration) -
         top * top / (2.0 * acceleration)) / top


@_compiled
def downhill_at(distances: np.ndarray, row: int, column: int, pool: int) -> float:
    """The way down the distance field at a cell (radians, robot frame; atan2(−∂y, −∂x)).

    The field is constant within each ``pool``-wide cell: the slope is taken
    between those coarse cells (central differences, one-sided at the edges).
    """
    rows = (distances.shape[0] + pool - 1) // pool
    columns = (distances.shape[1] + pool - 1) // pool
    i = min(row // pool, rows - 1)
    j = min(column // pool, columns - 1)

    if rows < 2:
        d_row = 0.0
    elif i == 0:
        d_row = _coarse(distances, 1, j, pool) - _coarse(distances, 0, j, pool)
    elif i == rows - 1:
        d_row = _coarse(distances, i, j, pool) - _coarse(distances, i - 1, j, pool)
    else:
        d_row = (_coarse(distances, i + 1, j, pool) - _coarse(distances, i - 1, j, pool)) / 2.0
    if columns < 2:
        d_column = 0.0
    elif j == 0:
        d_column = _coarse(distances, i, 1, pool) - _coarse(distances, i, 0, pool)
    elif j == columns - 1:
        d_column = _coarse(distances, i, j, pool) - _coarse(distances, i, j - 1, pool)
    else:
        d_column = (_coarse(distances, i, j + 1, pool) -
                    _coarse(distances, i, j - 1, pool)) / 2.0
    return math.atan2(-d_row, -d_column)


@_compiled
def _coarse(distances: np.ndarray, row: int, column: int, pool: int) -> float:
    """The field in coarse cell (row, column); unreachable counts as 1000 m."""
    value: float = distances[row * pool, column * pool]
    return value if math.isfinite(value) else 1e3


@_compiled
def clearance_near(returns: np.ndarray, starts: np.ndarray, per_side: int, bucket: float,
                   half_size: float, x: float, y: float, bound: float,
                   nearer: float, farther: float) -> float:
    """The exact clearance at a robot-frame point, or ``bound`` if it is more.

    The distance to the nearest of ``returns`` (rows x, y, how much nearer
    the return counts, at most ``nearer``, and whether it counts ``farther``:
    1 for walls and furniture; sorted into ``per_side`` × ``per_side`` buckets
    of ``bucket`` metres from −``half_size``, bucket k's rows
    ``starts[k]:starts[k + 1]``) less its own margin, looking only at the
    buckets within ``bound`` + ``nearer`` of the point.
    """
    best = bound
    reach = bound + nearer
    last = per_side - 1
    low_column = int(max(math.floor((x - reach + half_size) / bucket), 0.0))
    high_column = int(min(math.floor((x + reach + half_size) / bucket), last))
    low_row = int(max(math.floor((y - reach + half_size) / bucket), 0.0))
    high_row = int(min(math.floor((y + reach + half_size) / bucket), last))
    for row in range(low_row, high_row + 1):
        for column in range(low_column, high_column + 1):
            k = row * per_side + column
            for i in range(starts[k], starts[k + 1]):
                gap = _length(x - returns[i, 0], y - returns[i, 1]) - returns[i, 2] + \
                    farther * returns[i, 3]
                if gap < best:
                    best = gap
    return best


# ------------------------------------------------------------------ the open list


@_compiled
def _before(score_a: float, node_a: int, score_b: float, node_b: int) -> bool:
    return score_a < score_b or (score_a == score_b and node_a < node_b)


@_compiled
def _push(scores: np.ndarray, nodes: np.ndarray, size: int, score: float, node: int) -> int:
    """Push (score, node) on the heap of ``size`` entries; the new size."""
    i = size
    while i > 0:
        parent = (i - 1) // 2
        if not _before(score, node, scores[parent], nodes[parent]):
            break
        scores[i] = scores[parent]
        nodes[i] = nodes[parent]
        i = parent
    scores[i] = score
    nodes[i] = node
    return size + 1


@_compiled
def _pop(scores: np.ndarray, nodes: np.ndarray, size: int) -> int:
    """Remove the heap's first entry (read it from ``scores[0], nodes[0]`` before); new size."""
    size -= 1
    score, node = scores[size], nodes[size]
    i = 0
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        if child + 1 < size and _before(scores[child + 1], nodes[child + 1], scores[child],
                                        nodes[child]):
            child += 1
        if not _before(scores[child], nodes[child], score, node):
            break
        scores[i] = scores[child]
        nodes[i] = nodes[child]
        i = child
    if size > 0:
        scores[i] = score
        nodes[i] = node
    return size


# ------------------------------------------------------------------ the search


@_compiled
def search(padded: np.ndarray, half_size: float, resolution: float, distances: np.ndarray,
           pool: int, target_x: float, target_y: float, final: bool,
           vx0: float, vy0: float, wz0: float, omni: bool, spin: float,
           first_lattice: np.ndarray, deep_lattice: np.ndarray,
           static: float, inside: bool, start_clearance: float,
           linear: float, angular: float, linear_acceleration: float,
           angular_acceleration: float,
           step: float, depth_limit: int, max_expansions: int, batch: int, substeps: int,
           goal_tolerance: float, greed: float, speed_margin: float, turn_cost: float,
           held_w: float, hold_cost: float, final_turn_cost: float,
           returns: np.ndarray, starts: np.ndarray, per_side: int, bucket: float,
           nearer: float, slack: float, crawl: float, crawl_allowance: float,
           ) -> tuple[int, float, float, float, int, int]:
    """One cycle's best-first search over motion sequences.

    Pops up to ``batch`` nodes per expansion (the root alone, with the finer
    first lattice). A node whose sequence is ``depth_limit`` motions long, or
    ends within ``goal_tolerance`` of the target, is final: the first one popped
    wins. Without one within the budget, the deepest, then cheapest, node seen
    wins. A motion changes the velocity at a constant rate over its ``step`` and
    is admissible when the robot keeps ``static`` plus ``speed_margin`` × speed
    of clearance (``padded``: the local grid's clearance with a one-cell
    border) at the middle of each of its ``substeps``. Where a cell's clearance
    is within ``slack`` (what it may overstate the clearance anywhere in the
    cell) of what is needed, the exact clearance from the returns counts
    instead (``clearance_near``): the margin kept is then the true one,
    whatever the cells' size. A motion no faster than ``crawl`` needs only
    ``static``, walls and furniture (``returns`` marked wide) counting
    ``crawl_allowance`` farther: a robot at its margin can still edge along it
    or away, and through a doorway it meets at a slant. Not from anything
    narrow: an unpaired leg is never crept up to. The
    cost is time, plus
    ``turn_cost`` per rad/s of change in turn rate, and for the first motion
    ``hold_cost`` per rad/s its turn rate differs from ``held_w``, the one the
    last cycle chose (NaN: none), so that the plan does not flip from cycle to
    cycle between two nearly as good ones. On the ``final`` approach the turn
    rate's changes cost ``final_turn_cost`` instead, and there is no hysteresis
    (the caller passes NaN).

    Returns:
        (found, vx, vy, wz, expansions, depth): ``found`` is 0 when no motion is
        admissible, else 1 and the first motion's velocity of the winning sequence.
    """
    cells = padded.shape[0] - 2
    scale = 1.0 / resolution
    n_first = first_lattice.shape[0]
    n_deep = deep_lattice.shape[0]
    capacity = 1 + n_first + (max_expansions + batch) * n_deep
    # Per node: x, y, theta, vx, vy, wz, remaining path length; its first node, depth, cost.
    state = np.zeros((capacity, 7))
    first = np.zeros(capacity, dtype=np.int64)
    depth = np.zeros(capacity, dtype=np.int64)
    cost = np.zeros(capacity)
    heap_scores = np.zeros(capacity)
    heap_nodes = np.zeros(capacity, dtype=np.int64)
    parents = np.zeros(batch, dtype=np.int64)
    xs = np.zeros(substeps)
    ys = np.zeros(substeps)
    state[0, 3] = vx0
    state[0, 4] = vy0 if omni else 0.0
    state[0, 5] = wz0
    state[0, 6] = np.inf
    size = 1
    heap = _push(heap_scores, heap_nodes, 0, 0.0, 0)
    best_node = -1
    best_depth = 0
    best_score = 0.0
    expansions = 0
    dt = step / substeps
    while heap > 0 and expansions < max_expansions:
        count = 0
        while heap > 0 and count < batch and expansions < max_expansions:
            score, node = heap_scores[0], heap_nodes[0]
            heap = _pop(heap_scores, heap_nodes, heap)
            if node != 0 and (depth[node] >= depth_limit or state[node, 6] <= goal_tolerance):
                if count == 0:
                    f = first[node]
                    return 1, state[f, 3], state[f, 4], state[f, 5], expansions, depth[node]
                heap = _push(heap_scores, heap_nodes, heap, score, node)  # after this batch
                break
            parents[count] = node
            count += 1
            expansions += 1
            if node == 0:
                break  # the root expands alone, with the finer first lattice
        root = parents[0] == 0
        lattice = first_lattice if root else deep_lattice
        for p in range(count):
            parent = parents[p]
            sx, sy, sth = state[parent, 0], state[parent, 1], state[parent, 2]
            now_x, now_y, now_w = state[parent, 3], state[parent, 4], state[parent, 5]
            for m in range(lattice.shape[0]):
                end_x = now_x + lattice[m, 0]
                end_y = now_y + lattice[m, 1]
                end_w = min(max(now_w + lattice[m, 2], -angular), angular)
                if omni:
                    # Hardly backwards: the laser sees ahead and to the sides.
                    end_x = min(max(end_x, -0.1), linear)
                    if _length(end_x, end_y) > linear + 1e-9:
                        continue
                else:
                    end_x = min(max(end_x, 0.0), linear)
                change_x, change_y, change_w = end_x - now_x, end_y - now_y, end_w - now_w
                # Roll the motion out: the velocity in the middle of each substep.
                turned = 0.0
                moved_x = 0.0
                moved_y = 0.0
                ok = True
                last_clearance = 0.0
                th = sth
                for k in range(substeps):
                    fraction = (k + 0.5) / substeps
                    vx = now_x + fraction * change_x
                    vy = now_y + fraction * change_y
                    turn = (now_w + fraction * change_w) * dt
                    turned += turn
                    th = sth + turned
                    middle = th - turn / 2.0
                    cos, sin = math.cos(middle), math.sin(middle)
                    moved_x += (vx * cos - vy * sin) * dt
                    moved_y += (vx * sin + vy * cos) * dt
                    xs[k] = sx + moved_x
                    ys[k] = sy + moved_y
                    column = int(min(max((xs[k] + half_size) * scale + 1.0, 0.0), cells + 1.0))
                    row = int(min(max((ys[k] + half_size) * scale + 1.0, 0.0), cells + 1.0))
                    last_clearance = padded[row, column]
                    speed = _length(vx, vy) if omni else abs(vx)
                    # Crawling needs no margin for its speed (it stops within a period),
                    # and walls and furniture may count a little farther then.
                    crawling = speed <= crawl
                    need = static if crawling else static + speed_margin * speed
                    if last_clearance < need + slack:
                        # A cell's clearance is at most half its diagonal short of the
                        # exact one: with that bound every return that counts is seen.
                        farther = crawl_allowance if crawling else 0.0
                        last_clearance = clearance_near(
                            returns, starts, per_side, bucket, half_size, xs[k], ys[k],
                            last_clearance + slack / 3.0 + farther + 1e-9, nearer, farther)
                    if last_clearance < need:
                        ok = False
                        break
                if not ok:
                    continue
                if inside and last_clearance < start_clearance:
                    continue
                x, y = xs[substeps - 1], ys[substeps - 1]
                column = int(min(max((x + half_size) * scale, 0.0), cells - 1.0))
                row = int(min(max((y + half_size) * scale, 0.0), cells - 1.0))
                # The field is coarse; the straight distance is a bound that is exact near
                # the target.
                remaining = max(distances[row, column], _length(x - target_x, y - target_y))
                # At the goal, able to stop on it: v² ≤ 2·a·(distance left).
                if final and _length(end_x, end_y) > math.sqrt(
                        2.0 * linear_acceleration * max(remaining - 0.02, 0.0)) + 0.05:
                    continue
                # The time left: cover the distance from this speed, after turning where
                # needed (a differential base must face the way down the distance field,
                # and its speed counts only along that way).
                if omni:
                    to_go = _ramp_time(remaining, _length(end_x, end_y), linear,
                                       linear_acceleration)
                else:
                    if remaining > 0.15:
                        way = downhill_at(distances, row, column, pool)
                    else:
                        # So near, the coarse field's slope says nothing: the way is the
                        # straight line to the target (beside the robot, it must turn).
                        way = math.atan2(target_y - y, target_x - x)
                    # homebot.geometry.wrap_angle, written out: a compiled kernel calls no Python
                    error = (way - th + math.pi) % (2.0 * math.pi) - math.pi
                    if spin != 0.0 and abs(error) > 2.5 and error * spin < 0.0:
                        # The way lies behind: either turn will do, so keep turning the way
                        # it turns now (otherwise the choice flips and the robot dithers).
                        error += spin * 2.0 * math.pi
                    if _length(target_x - x, target_y - y) <= goal_tolerance or \
                            (final and remaining <= 0.15 and abs(error) < math.pi / 2):
                        # On the goal, or ahead of the robot close by at the end: no turn
                        # on the spot (beside it, though, the robot would circle it).
                        error = 0.0
                    along = max(end_x * math.cos(error), 0.0)
                    travel = _ramp_time(remaining, along, linear, linear_acceleration)
                    # Facing more than 45° off the way, a differential base turns on the
                    # spot (more or less) before it gets anywhere: that adds to the travel.
                    turning = _turn_time(max(abs(error) - math.pi / 4.0, 0.0),
                                         end_w * _sign(error), angular, angular_acceleration)
                    to_go = travel + turning
                child = size
                size += 1
                state[child, 0] = x
                state[child, 1] = y
                state[child, 2] = th
                state[child, 3] = end_x
                state[child, 4] = end_y
                state[child, 5] = end_w
                state[child, 6] = remaining
                first[child] = child if root else first[parent]
                depth[child] = depth[parent] + 1
                # Time is the cost, plus a little for every change of turn rate.
                cost[child] = cost[parent] + step + \
                    (final_turn_cost if final else turn_cost) * abs(change_w)
                if root and math.isfinite(held_w):
                    cost[child] += hold_cost * abs(end_w - held_w)
                score = cost[child] + greed * to_go
                heap = _push(heap_scores, heap_nodes, heap, score, child)
                # The deepest, then cheapest, then first node seen.
                if best_node < 0 or depth[child] > best_depth or \
                        (depth[child] == best_depth and score < best_score):
                    best_node, best_depth, best_score = child, depth[child], score
    if best_node < 0:
        return 0, 0.0, 0.0, 0.0, expansions, 0
    f = first[best_node]
    return 1, state[f, 3], state[f, 4], state[f, 5], expansions, best_depth


# ------------------------------------------------------------------ the search by length


@_compiled
def sweep(cost: np.ndarray, root_row: int, root_column: int, cardinal: int,
          diagonal: int) -> np.ndarray:
    """Dijkstra out from one cell over an 8-connected grid: every cell's least path cost.

    Entering a cell costs ``cardinal`` (straight) or ``diagonal`` times its
    ``cost``; a cell of cost 0 is blocked. Cells not reached hold the dtype's
    largest value (as libtcod's pathfinder, which this replaces, does).
    """
    rows, columns = cost.shape
    unreached = np.iinfo(np.int64).max
    distance = np.full((rows, columns), unreached, dtype=np.int64)
    capacity = 8 * rows * columns + 1
    heap_scores = np.zeros(capacity)
    heap_nodes = np.zeros(capacity, dtype=np.int64)
    distance[root_row, root_column] = 0
    heap = _push(heap_scores, heap_nodes, 0, 0.0, root_row * columns + root_column)
    while heap > 0:
        score, node = heap_scores[0], heap_nodes[0]
        heap = _pop(heap_scores, heap_nodes, heap)
        row, column = node // columns, node % columns
        here = distance[row, column]
        if score > here:
            continue  # a stale entry: a shorter way here was found meanwhile
        for d_row in range(-1, 2):
            for d_column in range(-1, 2):
                r, c = row + d_row, column + d_column
                if (d_row == 0 and d_column == 0) or r < 0 or r >= rows or c < 0 or \
                        c >= columns or cost[r, c] == 0:
                    continue
                step = cardinal if d_row == 0 or d_column == 0 else diagonal
                there = here + step * cost[r, c]
                if there < distance[r, c]:
                    distance[r, c] = there
                    heap = _push(heap_scores, heap_nodes, heap, float(there), r * columns + c)
    return distance


@_compiled
def coarse_field(clearance: np.ndarray, grown: float, pool: int, target_column: float,
                 target_row: float, speed_margin: float, top: float,
                 resolution: float) -> tuple[np.ndarray, bool]:
    """The search by length on cells ``pool`` times coarser (see ``LocalGrid.distance_field``).

    A coarse cell is free when any of its cells has ``grown`` clearance. With a
    ``top`` speed (> 0), entering a coarse cell costs its length times the
    slowness of its fastest clear cell: ``top`` over the speed its clearance
    allows (clearance beyond ``grown``, per ``speed_margin``, between 0.05 and
    ``top``). The target (coarse cell coordinates) moves to the nearest free cell.

    Returns:
        (metres from each coarse cell, inf where not reached; whether all were
        reached). No free cell at all: every cell inf.
    """
    cells = clearance.shape[0] - clearance.shape[0] % pool
    n = cells // pool
    free = np.zeros((n, n), dtype=np.bool_)
    cost = np.zeros((n, n), dtype=np.int32)
    any_free = False
    for i in range(n):
        for j in range(n):
            fastest = np.inf
            for a in range(pool):
                for b in range(pool):
                    value = clearance[i * pool + a, j * pool + b]
                    if value >= grown:
                        free[i, j] = True
                        if top > 0.0:
                            allowed = min(max((value - grown) / speed_margin, 0.05), top)
                            fastest = min(fastest, top / allowed)
            if free[i, j]:
                any_free = True
                cost[i, j] = np.int32(np.rint(min(fastest, 50.0) * 10)) if top > 0.0 else 1
    coarse = np.full((n, n), np.inf)
    if not any_free:
        return coarse, False
    column = int(min(max(target_column, 0.0), n - 1.0))
    row = int(min(max(target_row, 0.0), n - 1.0))
    if not free[row, column]:
        best, near_row, near_column = -1, row, column
        for i in range(n):
            for j in range(n):
                gap = (i - row) ** 2 + (j - column) ** 2
                if free[i, j] and (best < 0 or gap < best):
                    best, near_row, near_column = gap, i, j
        row, column = near_row, near_column
    unit = 1000 if top > 0.0 else 100  # raw distance per cell at top speed
    raw = sweep(cost, row, column, 100, 141)
    unreached = np.iinfo(np.int64).max
    everywhere = True
    scale = resolution / unit
    for i in range(n):
        for j in range(n):
            if raw[i, j] != unreached:
                coarse[i, j] = raw[i, j] * scale
            else:
                everywhere = False
    return coarse, everywhere


@_compiled
def expand(coarse: np.ndarray, pool: int, cells: int) -> np.ndarray:
    """``coarse`` back on the fine grid of ``cells``: each value ``pool`` × ``pool`` times,
    the last row and column repeated where ``cells`` is not a multiple of ``pool``."""
    n = coarse.shape[0]
    coarse_column = np.empty(cells, dtype=np.int64)
    for c in range(cells):
        coarse_column[c] = min(c // pool, n - 1)
    field = np.empty((cells, cells))
    for r in range(cells):
        i = min(r // pool, n - 1)
        for c in range(cells):
            field[r, c] = coarse[i, coarse_column[c]]
    return field


# ------------------------------------------------------------------ the local grid


@_compiled
def nearest_occupied(occupied: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per cell, the row and column of the nearest occupied cell, by an exact Euclidean
    distance transform (Felzenszwalb and Huttenlocher's: the nearest occupied row in each
    column, then per row the lower envelope of the parabolas those rows make). Rows and
    columns are −1 everywhere when no cell is occupied."""
    rows, columns = occupied.shape
    near_rows = np.full((rows, columns), -1, dtype=np.int64)
    near_columns = np.full((rows, columns), -1, dtype=np.int64)
    # Down each column: the nearest occupied row (−1: the column has none).
    column_near = np.full((rows, columns), -1, dtype=np.int64)
    for column in range(columns):
        last = -1
        for row in range(rows):
            if occupied[row, column]:
                last = row
            column_near[row, column] = last
        last = -1
        for row in range(rows - 1, -1, -1):
            if occupied[row, column]:
                last = row
            if last >= 0 and (column_near[row, column] < 0 or
                              last - row < row - column_near[row, column]):
                column_near[row, column] = last
    # Along each row: the lower envelope of (x − j)² + (row gap in column j)².
    sites = np.zeros(columns, dtype=np.int64)
    bounds = np.zeros(columns + 1)
    heights = np.zeros(columns)
    for row in range(rows):
        k = -1
        for q in range(columns):
            if column_near[row, q] < 0:
                continue
            gap = column_near[row, q] - row
            heights[q] = float(gap * gap + q * q)
            if k < 0:
                k = 0
                sites[0] = q
                bounds[0] = -np.inf
                bounds[1] = np.inf
                continue
            crossing = 0.0
            while True:
                crossing = (heights[q] - heights[sites[k]]) / (2.0 * (q - sites[k]))
                if crossing <= bounds[k]:
                    k -= 1
                else:
                    break
            k += 1
            sites[k] = q
            bounds[k] = crossing
            bounds[k + 1] = np.inf
        if k < 0:
            return near_rows, near_columns  # nothing occupied at all
        k = 0
        for column in range(columns):
            while bounds[k + 1] < column:
                k += 1
            near_columns[row, column] = sites[k]
            near_rows[row, column] = column_near[row, sites[k]]
    return near_rows, near_columns


@_compiled
def clearance_grid(points: np.ndarray, cells: int, half: float, resolution: float,
                   outside: float) -> np.ndarray:
    """Per cell of a ``cells`` × ``cells`` grid from −``half`` (rows along y), the distance
    from its centre to the point kept in its nearest occupied cell (the last point that fell
    in that cell); ``outside`` everywhere when no point falls in the grid."""
    clearance = np.full((cells, cells), outside)
    occupied = np.zeros((cells, cells), dtype=np.bool_)
    kept = np.zeros((cells, cells, 2))
    any_occupied = False
    for k in range(points.shape[0]):
        column = int(np.floor((points[k, 0] + half) / resolution))
        row = int(np.floor((points[k, 1] + half) / resolution))
        if 0 <= column < cells and 0 <= row < cells:
            occupied[row, column] = True
            kept[row, column, 0] = points[k, 0]
            kept[row, column, 1] = points[k, 1]
            any_occupied = True
    if not any_occupied:
        return clearance
    near_rows, near_columns = nearest_occupied(occupied)
    for row in range(cells):
        y = (row + 0.5) * resolution - half
        for column in range(cells):
            i, j = near_rows[row, column], near_columns[row, column]
            dx = kept[i, j, 0] - ((column + 0.5) * resolution - half)
            dy = kept[i, j, 1] - y
            clearance[row, column] = math.sqrt(dx * dx + dy * dy)
    return clearance


@_compiled
def fill_unreached(field: np.ndarray, resolution: float) -> np.ndarray:
    """``field`` (metres; inf where not reached) with each unreached cell given its nearest
    reached cell's value plus the straight way there (all inf when none was reached)."""
    rows, columns = field.shape
    reached = np.zeros((rows, columns), dtype=np.bool_)
    for row in range(rows):
        for column in range(columns):
            reached[row, column] = math.isfinite(field[row, column])
    near_rows, near_columns = nearest_occupied(reached)
    filled = field.copy()
    if near_rows[0, 0] < 0:
        return filled
    for row in range(rows):
        for column in range(columns):
            if not reached[row, column]:
                i, j = near_rows[row, column], near_columns[row, column]
                gap = math.sqrt(float((i - row) * (i - row) + (j - column) * (j - column)))
                filled[row, column] = field[i, j] + gap * resolution
    return filled


@_compiled
def bucketed(points: np.ndarray, nearer: np.ndarray, wide: np.ndarray, half: float,
             bucket: float, per_side: int) -> tuple[np.ndarray, np.ndarray]:
    """The points in a grid of ``per_side`` × ``per_side`` buckets (``bucket`` metres square,
    from −``half``) as (x, y, nearer, wide) rows sorted by bucket (in their order within
    one), and each bucket's first row (``per_side``² + 1 entries: a counting sort)."""
    count = points.shape[0]
    index = np.full(count, -1, dtype=np.int64)
    starts = np.zeros(per_side * per_side + 1, dtype=np.int64)
    for k in range(count):
        column = int(np.floor((points[k, 0] + half) / bucket))
        row = int(np.floor((points[k, 1] + half) / bucket))
        if 0 <= column < per_side and 0 <= row < per_side:
            index[k] = row * per_side + column
            starts[index[k] + 1] += 1
    for b in range(per_side * per_side):
        starts[b + 1] += starts[b]
    filled = starts[:-1].copy()
    rows = np.zeros((starts[-1], 4))
    for k in range(count):
        b = index[k]
        if b < 0:
            continue
        rows[filled[b], 0] = points[k, 0]
        rows[filled[b], 1] = points[k, 1]
        rows[filled[b], 2] = nearer[k]
        rows[filled[b], 3] = 1.0 if wide[k] else 0.0
        filled[b] += 1
    return rows, starts


@_compiled
def classify_returns(ranges: np.ndarray, xs: np.ndarray, ys: np.ndarray, jump: float,
                     small_extent: float, pair: float,
                     hidden_beams: int) -> tuple[np.ndarray, np.ndarray]:
    """Per beam, whether its return belongs to a leg and whether to a wide cluster.

    Beams are ``ranges`` (NaN: no return) with their returns at (``xs``, ``ys``).
    A cluster is a run of neighbouring beams whose ranges differ by less than
    ``jump``. A leg's cluster is narrower than ``small_extent``, in front of the
    beams either side of it (or of nothing there), and paired: another such
    cluster lies within ``pair``, or the next cluster in the sweep is a leg half
    hidden behind it (narrow, of ``hidden_beams`` beams at least, in front of
    its far side, within ``pair``). A cluster at least ``small_extent`` wide is
    a wall's or furniture's.
    """
    count = ranges.shape[0]
    small = np.zeros(count, dtype=np.bool_)
    wide = np.zeros(count, dtype=np.bool_)
    if count == 0:
        return small, wide
    # Clusters: where each starts and ends (NaN ranges never join a cluster).
    starts = np.empty(count, dtype=np.int64)
    clusters = 0
    for i in range(count):
        if i == 0 or not abs(ranges[i] - ranges[i - 1]) < jump:
            starts[clusters] = i
            clusters += 1
    ends = np.empty(clusters, dtype=np.int64)
    for c in range(clusters - 1):
        ends[c] = starts[c + 1] - 1
    ends[clusters - 1] = count - 1
    narrow = np.zeros(clusters, dtype=np.bool_)
    is_wide = np.zeros(clusters, dtype=np.bool_)
    free = np.zeros(clusters, dtype=np.bool_)
    nearer_before = np.zeros(clusters, dtype=np.bool_)
    nearer_after = np.zeros(clusters, dtype=np.bool_)
    middle_x = np.empty(clusters)
    middle_y = np.empty(clusters)
    for c in range(clusters):
        s, e = starts[c], ends[c]
        extent = math.hypot(xs[e] - xs[s], ys[e] - ys[s])
        before = ranges[s - 1] if s > 0 else np.inf
        after = ranges[e + 1] if e < count - 1 else np.inf
        if math.isnan(before):
            before = np.inf
        if math.isnan(after):
            after = np.inf
        nearer_before[c] = before > ranges[s] + jump
        nearer_after[c] = after > ranges[e] + jump
        narrow[c] = extent < small_extent and math.isfinite(ranges[s])
        is_wide[c] = extent >= small_extent
        free[c] = narrow[c] and nearer_before[c] and nearer_after[c]
        middle_x[c] = (xs[s] + xs[e]) / 2.0
        middle_y[c] = (ys[s] + ys[e]) / 2.0
    leg = np.zeros(clusters, dtype=np.bool_)
    for a in range(clusters):
        if not free[a]:
            continue
        for b in range(clusters):
            if b != a and free[b] and \
                    math.hypot(middle_x[a] - middle_x[b], middle_y[a] - middle_y[b]) < pair:
                leg[a] = True
                break
    # Or one leg half hidden behind the other: the cluster next to a free one in the sweep.
    for c in range(clusters - 1):
        if not math.hypot(middle_x[c + 1] - middle_x[c], middle_y[c + 1] - middle_y[c]) < pair:
            continue
        hidden_after = narrow[c + 1] and ends[c + 1] - starts[c + 1] + 1 >= hidden_beams
        hidden_before = narrow[c] and ends[c] - starts[c] + 1 >= hidden_beams
        if (free[c] and hidden_after and nearer_after[c + 1]) or \
                (free[c + 1] and hidden_before and nearer_before[c]):
            leg[c] = True
            leg[c + 1] = True
    for c in range(clusters):
        for i in range(starts[c], ends[c] + 1):
            small[i] = leg[c]
            wide[i] = is_wide[c]
    return small, wide
