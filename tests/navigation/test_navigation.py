"""Grid, A*, topological routing; closed doors and people in doorways block routes."""

from __future__ import annotations

import itertools
import math

import numpy as np

from homebot.navigation import Navigator, astar
from homebot.world import World


def _approach(world: World, name: str) -> tuple[float, float]:
    return world.placements[name].approach.xy()


def test_astar_finds_the_octile_shortest_path_on_open_floor() -> None:
    grid = np.zeros((50, 50), dtype=bool)
    path = astar(grid.ravel(), grid.shape, 0, 49 * 50 + 49)
    assert path is not None
    assert len(path) == 50  # straight diagonal


def test_astar_goes_round_a_wall_and_never_cuts_corners() -> None:
    grid = np.zeros((20, 20), dtype=bool)
    grid[0:15, 10] = True
    path = astar(grid.ravel(), grid.shape, 0, 19)
    assert path is not None
    cells = [divmod(cell, 20) for cell in path]
    assert all(not grid[r, c] for r, c in cells)
    assert max(r for r, _ in cells) >= 15
    for (r1, c1), (r2, c2) in itertools.pairwise(cells):
        if r1 != r2 and c1 != c2:
            assert not grid[r1, c2] and not grid[r2, c1]


def test_astar_reports_unreachable_goals() -> None:
    grid = np.zeros((10, 10), dtype=bool)
    grid[:, 5] = True
    assert astar(grid.ravel(), grid.shape, 0, 9) is None


def test_plan_passes_through_doors_in_order(apartment: World,
                                           apartment_navigator: Navigator) -> None:
    plan = apartment_navigator.plan(_approach(apartment, "bed"), _approach(apartment, "fridge"))
    assert plan is not None
    assert plan.doors == ("bedroom door", "kitchen door")
    assert plan.route.rooms == ("bedroom", "corridor", "kitchen")
    straight = math.dist(_approach(apartment, "bed"), _approach(apartment, "fridge"))
    assert straight < plan.length < 2 * straight


def test_path_stays_on_free_cells(apartment: World, apartment_navigator: Navigator) -> None:
    plan = apartment_navigator.plan(_approach(apartment, "couch"), _approach(apartment, "desk"))
    assert plan is not None
    for a, b in zip(plan.waypoints[1:-1], plan.waypoints[2:-1], strict=False):
        for t in np.linspace(0, 1, 10):
            x, y = a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])
            row, column = apartment_navigator.grid.cell_of(x, y)
            assert not apartment_navigator.grid.occupied[row, column]


def test_closed_door_reroutes_or_blocks(apartment: World, apartment_navigator: Navigator) -> None:
    couch, fridge = _approach(apartment, "couch"), _approach(apartment, "fridge")
    open_plan = apartment_navigator.plan(couch, fridge)
    assert open_plan is not None and "living room arch" in open_plan.doors
    rerouted = apartment_navigator.plan(couch, fridge, frozenset({"living room arch"}))
    assert rerouted is not None and "living room arch" not in rerouted.doors
    assert rerouted.length > open_plan.length
    shut_in = apartment_navigator.plan(_approach(apartment, "bed"), fridge,
                                       frozenset({"bedroom door"}))
    assert shut_in is None


def test_topological_route_avoids_closed_doors(apartment_navigator: Navigator) -> None:
    route = apartment_navigator.topology.route("living room", "kitchen",
                                               frozenset({"living room arch"}))
    assert route is not None
    assert route.doors[0] == "living room door"
    assert "living room arch" not in route.doors
    assert route.rooms[0] == "living room" and route.rooms[-1] == "kitchen"
    assert apartment_navigator.topology.route("bedroom", "kitchen",
                                              frozenset({"bedroom door"})) is None


def test_grid_marks_walls_furniture_and_door_openings(apartment: World,
                                                      apartment_navigator: Navigator) -> None:
    grid = apartment_navigator.grid
    assert grid.occupied[grid.cell_of(9.5, 1.8)]  # kitchen table
    assert grid.occupied[grid.cell_of(1.0, 4.0)]  # wall between living room and corridor
    assert not grid.occupied[grid.cell_of(2.5, 4.0)]  # the living room door's opening
    assert not grid.blocked[grid.cell_of(2.5, 4.0)]  # wide enough for the robot
