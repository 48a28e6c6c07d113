"""The occupancy grid: walls, door openings and furniture rasterised from a world."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy import ndimage
from shapely.geometry.base import BaseGeometry

from homebot.world.model import PlacementKind
from homebot.world.world import World

__all__ = ["OccupancyGrid"]

# Margin of free space drawn around the rooms' bounding box, in metres.
_MARGIN = 0.2


@dataclass(frozen=True)
class OccupancyGrid:
    """A 2-D grid of the home seen by a robot of a given radius.

    ``occupied`` marks walls and furniture; ``blocked`` additionally marks every
    cell the robot's centre cannot occupy (``occupied`` inflated by the robot
    radius). ``door_cells`` holds, per door, the flat indices that close the
    opening when the door is shut or someone stands in it; ``door_passages`` the
    cells of the opening itself, which a path going through the door crosses.
    """

    origin: tuple[float, float]
    resolution: float
    shape: tuple[int, int]  # (rows along y, columns along x)
    occupied: np.ndarray
    blocked: np.ndarray
    door_cells: dict[str, np.ndarray]
    door_passages: dict[str, np.ndarray]

    @classmethod
    def from_world(cls, world: World, robot_radius: float | None = None,
                   resolution: float | None = None) -> OccupancyGrid:
        """Rasterise ``world``; walls are drawn along every room boundary except door openings."""
        resolution = resolution or world.model.grid_resolution
        radius = world.robot.radius if robot_radius is None else robot_radius
        min_x, min_y, max_x, max_y = world.bounds()
        origin = (min_x - _MARGIN, min_y - _MARGIN)
        columns = int(np.ceil((max_x - min_x + 2 * _MARGIN) / resolution))
        rows = int(np.ceil((max_y - min_y + 2 * _MARGIN) / resolution))
        xs = origin[0] + (np.arange(columns) + 0.5) * resolution
        ys = origin[1] + (np.arange(rows) + 0.5) * resolution
        grid_x, grid_y = np.meshgrid(xs, ys)

        inside = np.zeros((rows, columns), dtype=bool)
        wall = np.zeros((rows, columns), dtype=bool)
        half_wall = world.model.wall_thickness / 2
        for polygon in world.room_polygons.values():
            inside |= _contains(polygon, grid_x, grid_y)
            wall |= _within(polygon.exterior, grid_x, grid_y, half_wall, resolution)
        door_cells: dict[str, np.ndarray] = {}
        door_passages: dict[str, np.ndarray] = {}
        for door in world.doors.values():
            distance = np.hypot(grid_x - door.position[0], grid_y - door.position[1])
            wall &= ~(distance <= door.width / 2)
            in_wall = _within(world.room_polygons[door.rooms[0]].exterior, grid_x, grid_y,
                              half_wall + resolution, resolution,
                              near=shapely.Point(door.position).buffer(door.width / 2))
            door_passages[door.name] = np.flatnonzero((distance <= door.width / 2) & in_wall)
            # A shut door (or a person in it) fills the opening and a little more,
            # so the inflated gap is closed whatever the robot's radius.
            door_cells[door.name] = np.flatnonzero(distance <= door.width / 2 + 0.05)
        occupied = ~inside | wall
        for placement in world.placements.values():
            if placement.model.kind is PlacementKind.FURNITURE:
                occupied |= _contains(placement.footprint, grid_x, grid_y)
        clearance = ndimage.distance_transform_edt(~occupied) * resolution
        blocked = clearance < radius
        return cls(origin, resolution, (rows, columns), occupied, blocked, door_cells,
                   door_passages)

    def cell_of(self, x: float, y: float) -> tuple[int, int]:
        """(row, column) of the cell containing the point, clipped to the grid."""
        column = int((x - self.origin[0]) / self.resolution)
        row = int((y - self.origin[1]) / self.resolution)
        return (min(max(row, 0), self.shape[0] - 1), min(max(column, 0), self.shape[1] - 1))

    def center_of(self, row: int, column: int) -> tuple[float, float]:
        """The world coordinates of a cell's centre."""
        return (self.origin[0] + (column + 0.5) * self.resolution,
                self.origin[1] + (row + 0.5) * self.resolution)

    def blocked_with(self, closed_doors: frozenset[str]) -> np.ndarray:
        """The ``blocked`` mask with the given doors shut, flattened."""
        mask = self.blocked.ravel().copy()
        for door in closed_doors:
            mask[self.door_cells[door]] = True
        return mask

    def nearest_free(self, mask: np.ndarray, row: int, column: int) -> tuple[int, int] | None:
        """The free cell of ``mask`` (flat) nearest to (row, column), searched in rings."""
        rows, columns = self.shape
        flat = mask.reshape(self.shape)
        if not flat[row, column]:
            return (row, column)
        for ring in range(1, max(rows, columns)):
            top, bottom = max(row - ring, 0), min(row + ring, rows - 1)
            left, right = max(column - ring, 0), min(column + ring, columns - 1)
            window = flat[top:bottom + 1, left:right + 1]
            free = np.argwhere(~window)
            if free.size:
                offsets = np.add(free, (top, left))
                best = np.argmin(np.hypot(offsets[:, 0] - row, offsets[:, 1] - column))
                return (int(offsets[best, 0]), int(offsets[best, 1]))
        return None


def _within(line: BaseGeometry, grid_x: np.ndarray, grid_y: np.ndarray, reach: float,
            resolution: float, near: BaseGeometry | None = None) -> np.ndarray:
    """Cells whose centres lie within ``reach`` of ``line``; with ``near``, only those near
    that shape are looked at (the rest are False).

    Exact distances are taken only for the cells inside the line's buffer grown by a cell,
    which holds every cell within reach: a whole-grid distance costs seconds at the
    simulator's 2 cm."""
    band: BaseGeometry = line.buffer(reach + resolution)
    if near is not None:
        band = band.intersection(near.buffer(resolution))
    candidates = _contains(band, grid_x, grid_y)
    xs, ys = grid_x[candidates], grid_y[candidates]
    close = shapely.distance(line, shapely.points(xs, ys)) <= reach
    result = np.zeros(grid_x.shape, dtype=bool)
    result[candidates] = close
    return result


def _contains(shape: BaseGeometry, grid_x: np.ndarray, grid_y: np.ndarray) -> np.ndarray:
    """Cells whose centres lie inside ``shape``, testing only those in its bounding box."""
    inside = np.zeros(grid_x.shape, dtype=bool)
    min_x, min_y, max_x, max_y = shape.bounds
    columns = (grid_x[0] >= min_x) & (grid_x[0] <= max_x)
    rows = (grid_y[:, 0] >= min_y) & (grid_y[:, 0] <= max_y)
    box = np.ix_(rows, columns)
    inside[box] = shapely.contains_xy(shape, grid_x[box], grid_y[box])
    return inside
