"""The home's solid matter as the simulator's ground truth: what a laser hits, what a base bumps.

Two forms of the same geometry, built once per world and shared between runs:
a fine raster (2 cm), for ray casting, and exact
shapely shapes, for judging collisions. Door states change which door
openings are filled, and where a door left ajar (``opening`` in the world file)
has its leaf: shut in the doorway, standing at its angle while open, or swung
back flat against the wall once someone opened the door wide; the raster is kept
per set of shut doors and of leaves swung back.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field

import numpy as np
import shapely
from shapely.geometry import Point
from shapely.geometry.base import BaseGeometry

from homebot.world import OccupancyGrid, PlacementKind, World

__all__ = ["TRUTH_RESOLUTION", "TrueGeometry"]

TRUTH_RESOLUTION = 0.02  #: metres per cell of the ray-casting raster

_CACHE: weakref.WeakKeyDictionary[World, TrueGeometry] = weakref.WeakKeyDictionary()


@dataclass
class TrueGeometry:
    """Walls, door leaves and furniture of one world."""

    world: World
    raster: OccupancyGrid = field(init=False)
    _walls: BaseGeometry = field(init=False)
    _door_leaves: dict[str, BaseGeometry] = field(init=False)
    _open_leaves: dict[str, BaseGeometry] = field(init=False)
    _images: dict[tuple[frozenset[str], frozenset[str]], np.ndarray] = field(
        init=False, default_factory=dict)
    _solids: dict[tuple[frozenset[str], frozenset[str]], BaseGeometry] = field(
        init=False, default_factory=dict)

    @classmethod
    def of(cls, world: World) -> TrueGeometry:
        """The geometry of ``world``, built on first use and then shared."""
        if world not in _CACHE:
            _CACHE[world] = cls(world)
        return _CACHE[world]

    def __post_init__(self) -> None:
        world = self.world
        self.raster = OccupancyGrid.from_world(world, robot_radius=0.0,
                                               resolution=TRUTH_RESOLUTION)
        half_wall = world.model.wall_thickness / 2
        walls = shapely.union_all([polygon.exterior.buffer(half_wall, cap_style="flat")
                                   for polygon in world.room_polygons.values()])
        openings = {name: Point(door.position).buffer(door.width / 2)
                    for name, door in world.doors.items()}
        if openings:
            walls = walls.difference(shapely.union_all(list(openings.values())))
        furniture = [p.footprint for p in world.placements.values()
                     if p.model.kind is PlacementKind.FURNITURE]
        self._walls = shapely.union_all([walls, *furniture])
        wall_band = shapely.union_all([polygon.exterior.buffer(half_wall + 0.01)
                                       for polygon in world.room_polygons.values()])
        self._door_leaves = {name: opening.intersection(wall_band)
                             for name, opening in openings.items()}
        self._open_leaves = {name: leaf for name in world.doors
                             if (leaf := world.door_leaf(name)) is not None}

    def solid_image(self, shut_doors: frozenset[str],
                    swung_back: frozenset[str] = frozenset()) -> np.ndarray:
        """The raster with these doors shut and these leaves swung back flat against the
        wall (no longer standing ajar): 1 where solid, 0 where free (uint8, row = y)."""
        key = (shut_doors, swung_back)
        if key not in self._images:
            occupied = self.raster.occupied.ravel().copy()
            for door in shut_doors:
                occupied[self.raster.door_passages[door]] = True
            for door, leaf in self._open_leaves.items():
                if door not in shut_doors and door not in swung_back:
                    occupied[self._cells_under(leaf)] = True
            self._images[key] = occupied.reshape(self.raster.shape).astype(np.uint8)
        return self._images[key]

    def solids(self, shut_doors: frozenset[str],
               swung_back: frozenset[str] = frozenset()) -> BaseGeometry:
        """Walls, furniture, the leaves of the shut doors and those standing ajar (not
        ``swung_back``), as one prepared shape."""
        key = (shut_doors, swung_back)
        if key not in self._solids:
            leaves = [self._door_leaves[door] for door in sorted(shut_doors)] + [
                leaf for door, leaf in sorted(self._open_leaves.items())
                if door not in shut_doors and door not in swung_back]
            solid = shapely.union_all([self._walls, *leaves])
            shapely.prepare(solid)
            self._solids[key] = solid
        return self._solids[key]

    def _cells_under(self, shape: BaseGeometry) -> np.ndarray:
        """Flat indices of the raster cells whose centres lie within ``shape`` grown by half
        a cell's diagonal, so that a thin leaf is drawn without gaps."""
        raster = self.raster
        grown = shape.buffer(TRUTH_RESOLUTION * 0.71)
        rows, columns = raster.shape
        min_x, min_y, max_x, max_y = grown.bounds
        first_column = max(int((min_x - raster.origin[0]) / TRUTH_RESOLUTION), 0)
        last_column = min(int((max_x - raster.origin[0]) / TRUTH_RESOLUTION) + 1, columns - 1)
        first_row = max(int((min_y - raster.origin[1]) / TRUTH_RESOLUTION), 0)
        last_row = min(int((max_y - raster.origin[1]) / TRUTH_RESOLUTION) + 1, rows - 1)
        row_index, column_index = np.mgrid[first_row:last_row + 1, first_column:last_column + 1]
        xs = raster.origin[0] + (column_index + 0.5) * TRUTH_RESOLUTION
        ys = raster.origin[1] + (row_index + 0.5) * TRUTH_RESOLUTION
        inside = shapely.contains_xy(grown, xs, ys)
        flat: np.ndarray = (row_index[inside] * columns + column_index[inside]).astype(np.intp)
        return flat

    def clearance(self, x: float, y: float, shut_doors: frozenset[str],
                  swung_back: frozenset[str] = frozenset()) -> float:
        """Exact distance from a point to the nearest wall, furniture, shut door or leaf
        standing ajar."""
        return float(shapely.distance(self.solids(shut_doors, swung_back), Point(x, y)))
