"""The occupancy grid, rasterised near each shape only, equals a whole-grid exact test."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from homebot.world import OccupancyGrid, PlacementKind, World


def _occupied_by_brute_force(world: World, grid: OccupancyGrid) -> np.ndarray:
    rows, columns = grid.shape
    xs = grid.origin[0] + (np.arange(columns) + 0.5) * grid.resolution
    ys = grid.origin[1] + (np.arange(rows) + 0.5) * grid.resolution
    grid_x, grid_y = np.meshgrid(xs, ys)
    points = shapely.points(grid_x, grid_y)
    inside = np.zeros(grid.shape, dtype=bool)
    wall = np.zeros(grid.shape, dtype=bool)
    for polygon in world.room_polygons.values():
        inside |= shapely.contains_xy(polygon, grid_x, grid_y)
        wall |= shapely.distance(polygon.exterior, points) <= world.model.wall_thickness / 2
    for door in world.doors.values():
        wall &= np.hypot(grid_x - door.position[0], grid_y - door.position[1]) > door.width / 2
    furniture = np.zeros(grid.shape, dtype=bool)
    for placement in world.placements.values():
        if placement.model.kind is PlacementKind.FURNITURE:
            furniture |= shapely.contains_xy(placement.footprint, grid_x, grid_y)
    return ~inside | wall | furniture


@pytest.mark.parametrize(("name", "resolution"), [("apartment", 0.05), ("family_home", 0.03)])
def test_occupied_cells_match_exact_distances_everywhere(name: str, resolution: float) -> None:
    world = World.load(name)
    grid = OccupancyGrid.from_world(world, robot_radius=0.0, resolution=resolution)
    assert np.array_equal(grid.occupied, _occupied_by_brute_force(world, grid))


def test_every_door_has_a_passage_through_its_wall() -> None:
    world = World.load("apartment")
    grid = OccupancyGrid.from_world(world, robot_radius=0.0, resolution=0.05)
    for door in world.doors.values():
        passage = grid.door_passages[door.name]
        assert passage.size > 0
        assert not grid.occupied.ravel()[passage].any()
        assert set(passage) <= set(grid.door_cells[door.name])
