"""The home's solid matter as the simulator's ground truth: what a laser hits, what a base bumps.

Two forms of the same geometry, built once per world and shared between runs:
a fine raster (2 cm), for ray casting, and exact
shapely shapes, for judging collisions. Door states change which door
openings are filled; the raster is kept per set of shut doors.
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
    _images: dict[frozenset[str], np.ndarray] = field(init=False, default_factory=dict)
    _solids: dict[frozenset[str], BaseGeometry] = field(init=False, default_factory=dict)

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

    def solid_image(self, shut_doors: frozenset[str]) -> np.ndarray:
        """The raster with these doors shut: 1 where solid, 0 where free (uint8, row = y)."""
        if shut_doors not in self._images:
            occupied = self.raster.occupied.ravel().copy()
            for door in shut_doors:
                occupied[self.raster.door_passages[door]] = True
            self._images[shut_doors] = occupied.reshape(self.raster.shape).astype(np.uint8)
        return self._images[shut_doors]

    def solids(self, shut_doors: frozenset[str]) -> BaseGeometry:
        """Walls, furniture and the leaves of the shut doors, as one prepared shape."""
        if shut_doors not in self._solids:
            leaves = [self._door_leaves[door] for door in sorted(shut_doors)]
            solid = shapely.union_all([self._walls, *leaves])
            shapely.prepare(solid)
            self._solids[shut_doors] = solid
        return self._solids[shut_doors]

    def clearance(self, x: float, y: float, shut_doors: frozenset[str]) -> float:
        """Exact distance from a point to the nearest wall, furniture or shut door."""
        return float(shapely.distance(self.solids(shut_doors), Point(x, y)))
