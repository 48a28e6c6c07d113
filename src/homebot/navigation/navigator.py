"""``Navigator``: metric paths on the grid, routed through the topological map."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage

from homebot.navigation.astar import astar
from homebot.navigation.topology import TopologicalMap
from homebot.world import NavigationPlan, OccupancyGrid, World

__all__ = ["Navigator", "point_along", "polyline_length"]

# Metres round the start and goal of plan_around where only the robot's radius is kept clear.
_END_ALLOWANCE = 0.6
# How many path segments a navigator remembers; fetch-and-deliver tasks revisit the same places.
_CACHE_SIZE = 4096


@dataclass
class Navigator:
    """Plans paths in one world for one robot radius.

    ``plan`` first asks the topological map whether the goal room is reachable
    with the given doors shut (fast, and it names the doors on the way), then
    runs A* on the occupancy grid for the metric path.
    """

    world: World
    grid: OccupancyGrid = field(init=False)
    topology: TopologicalMap = field(init=False)
    _masks: dict[frozenset[str], np.ndarray] = field(init=False, default_factory=dict)
    _cache: dict[tuple[int, int, frozenset[str]], list[int] | None] = field(
        init=False, default_factory=dict)
    _static_clearance: np.ndarray | None = field(init=False, default=None)

    def __post_init__(self) -> None:
        self.grid = OccupancyGrid.from_world(self.world)
        self.topology = TopologicalMap(self.world)

    def plan(self, start: tuple[float, float], goal: tuple[float, float],
             closed_doors: frozenset[str] = frozenset()) -> NavigationPlan | None:
        """A path from ``start`` to ``goal`` avoiding shut doors, or None if there is none.

        The topological route fixes the doors to pass; A* then runs on the grid
        from door to door (CAESAR's global/local split), which keeps each search
        inside one room where the octile heuristic is nearly exact. Start and
        goal are snapped to the nearest free cell, so a goal on the edge of
        furniture (a person sitting on the couch) is still reachable.
        """
        start_room, goal_room = self.world.room_at(*start), self.world.room_at(*goal)
        if start_room is None or goal_room is None:
            return None
        route = self.topology.route(start_room, goal_room, closed_doors, start, goal)
        if route is None:
            return None
        mask = self._mask(closed_doors)
        start_cell = self.grid.nearest_free(mask, *self.grid.cell_of(*start))
        goal_cell = self.grid.nearest_free(mask, *self.grid.cell_of(*goal))
        if start_cell is None or goal_cell is None:
            return None
        columns = self.grid.shape[1]
        stops = [start_cell[0] * columns + start_cell[1]]
        for door in route.doors:
            row, column = self.grid.cell_of(*self.world.doors[door].position)
            stops.append(row * columns + column)
        stops.append(goal_cell[0] * columns + goal_cell[1])
        cells: list[int] = [stops[0]]
        for here, there in itertools.pairwise(stops):
            segment = self._segment(here, there, closed_doors, mask)
            if segment is None:
                return None
            cells.extend(segment[1:])
        points = [self.grid.center_of(*divmod(cell, columns)) for cell in cells]
        length = polyline_length(points)
        length += math.dist(start, points[0]) + math.dist(goal, points[-1])
        waypoints = (start, *_simplify(points)[1:-1], goal)
        return NavigationPlan(waypoints, length, route.doors, route)

    def plan_around(self, start: tuple[float, float], goal: tuple[float, float],
                    closed_doors: frozenset[str], obstacles: np.ndarray,
                    clearance: float, static_clearance: float | None = None,
                    near_goal: float = 0.0, flat: np.ndarray | None = None,
                    flat_clearance: float = 0.0) -> tuple[tuple[float, float], ...] | None:
        """Waypoints of a path keeping ``clearance`` from ``obstacles`` ((n, 2) map points).

        CAESAR's dynamic obstacle extension: what the laser sees that the static map
        lacks (people, a chair moved) is drawn into the grid, and A* plans round it.
        One search over the whole grid, uncached, since the obstacles change.
        ``static_clearance`` (default: the robot's radius) is kept from walls and
        furniture: a local planner that keeps a safety margin needs the same here.
        When ``obstacles`` cover the goal itself (someone stands on it), the path ends
        at the free cell nearest to it if that lies within ``near_goal`` metres (as near
        as the robot can come), else there is none. ``flat`` are obstacles of something
        long and flat (a door's leaf left half open), kept ``flat_clearance`` from.
        """
        grid = self.grid
        mask = self._mask(closed_doors).copy()
        if static_clearance is not None:
            narrow = (self.clearance() < static_clearance).ravel()
            # Near its ends a path may pass as close as the robot's radius: approach
            # poses stand close to furniture on purpose.
            narrow[self._cells_within(np.asarray([start, goal]), _END_ALLOWANCE)] = False
            mask |= narrow
        if len(obstacles):
            mask[self._cells_within(obstacles, clearance)] = True
        if flat is not None and len(flat):
            mask[self._cells_within(flat, flat_clearance)] = True
        start_cell = grid.nearest_free(mask, *grid.cell_of(*start))
        goal_cell = grid.nearest_free(self._mask(closed_doors), *grid.cell_of(*goal))
        if start_cell is None or goal_cell is None:
            return None
        columns = grid.shape[1]
        goal_index = goal_cell[0] * columns + goal_cell[1]
        end = goal
        if mask[goal_index]:  # something stands on the goal itself
            near = grid.nearest_free(mask, *goal_cell) if near_goal > 0 else None
            if near is None or math.dist(grid.center_of(*near), goal) > near_goal:
                return None
            goal_index, end = near[0] * columns + near[1], grid.center_of(*near)
        cells_path = astar(mask, grid.shape, start_cell[0] * columns + start_cell[1], goal_index)
        if cells_path is None:
            return None
        points = [grid.center_of(*divmod(cell, columns)) for cell in cells_path]
        return (start, *_simplify(points)[1:-1], end)

    def _cells_within(self, points: np.ndarray, radius: float) -> np.ndarray:
        """Flat indices of the cells within ``radius`` of any of ``points`` ((n, 2), metres)."""
        grid = self.grid
        reach = int(np.ceil(radius / grid.resolution))
        rows, columns = grid.shape
        offsets = np.arange(-reach, reach + 1)
        dr, dc = np.meshgrid(offsets, offsets, indexing="ij")
        disc = np.hypot(dr, dc) * grid.resolution <= radius
        cells = np.array([grid.cell_of(x, y) for x, y in points])
        r = (cells[:, 0, None] + dr[disc][None, :]).ravel()
        c = (cells[:, 1, None] + dc[disc][None, :]).ravel()
        keep = (r >= 0) & (r < rows) & (c >= 0) & (c < columns)
        flat: np.ndarray = r[keep] * columns + c[keep]
        return flat

    def clearance(self) -> np.ndarray:
        """Metres from each cell centre to the nearest wall or furniture cell."""
        if self._static_clearance is None:
            self._static_clearance = ndimage.distance_transform_edt(
                ~self.grid.occupied) * self.grid.resolution
        return self._static_clearance

    def clearance_at(self, x: float, y: float) -> float:
        """Metres from the map cell under ``(x, y)`` to the nearest wall or furniture cell
        (0 off the map's grid)."""
        row, column = self.grid.cell_of(x, y)
        clearance = self.clearance()
        if not (0 <= row < clearance.shape[0] and 0 <= column < clearance.shape[1]):
            return 0.0
        return float(clearance[row, column])

    def distance(self, start: tuple[float, float], goal: tuple[float, float],
                 closed_doors: frozenset[str] = frozenset()) -> float:
        """Path length from start to goal (infinite when unreachable)."""
        plan = self.plan(start, goal, closed_doors)
        return plan.length if plan else math.inf

    def _mask(self, closed_doors: frozenset[str]) -> np.ndarray:
        if closed_doors not in self._masks:
            self._masks[closed_doors] = self.grid.blocked_with(closed_doors)
        return self._masks[closed_doors]

    def _segment(self, start: int, goal: int, closed_doors: frozenset[str],
                 mask: np.ndarray) -> list[int] | None:
        key = (start, goal, closed_doors)
        if key not in self._cache:
            if len(self._cache) >= _CACHE_SIZE:
                self._cache.clear()
            self._cache[key] = astar(mask, self.grid.shape, start, goal)
        return self._cache[key]


def _simplify(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """Drop waypoints that lie on a straight line between their neighbours."""
    if len(points) <= 2:
        return points
    kept = [points[0]]
    for previous, current, following in zip(points, points[1:], points[2:], strict=False):
        direction_in = (current[0] - previous[0], current[1] - previous[1])
        direction_out = (following[0] - current[0], following[1] - current[1])
        if abs(direction_in[0] * direction_out[1] - direction_in[1] * direction_out[0]) > 1e-9:
            kept.append(current)
    kept.append(points[-1])
    return kept


def polyline_length(points: Sequence[tuple[float, float]]) -> float:
    """The length of the polyline through ``points``, metres."""
    return sum(math.dist(a, b) for a, b in itertools.pairwise(points))


def point_along(points: Sequence[tuple[float, float]], distance: float
                ) -> tuple[tuple[float, float], float] | None:
    """The point ``distance`` metres along the polyline through ``points`` and its heading
    there; None when the polyline is shorter."""
    for a, b in itertools.pairwise(points):
        length = math.dist(a, b)
        if length > 0 and distance <= length:
            t = distance / length
            return ((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])),
                    math.atan2(b[1] - a[1], b[0] - a[0]))
        distance -= length
    return None
