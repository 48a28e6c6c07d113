"""Object positions on surfaces (given or seeded) and the side a placement faces."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import Point

from homebot.errors import WorldError
from homebot.world import World, front_heading, object_positions


def test_sampled_positions_lie_on_their_placement_and_follow_the_seed() -> None:
    world = World.load("apartment")
    positions = object_positions(world, seed=7)
    assert set(positions) == set(world.objects)
    for name, point in positions.items():
        assert world.placements[world.objects[name].placement].footprint.covers(Point(point))
    assert positions == object_positions(world, seed=7)
    assert positions != object_positions(world, seed=8)


def test_a_given_position_is_kept_and_one_off_the_surface_is_refused() -> None:
    data = World.load("apartment").to_dict()
    table = next(p for p in data["placements"] if p["name"] == "kitchen table")
    x, y = table["center"]
    data["objects"].append({"name": "red cup", "category": "dish", "placement": "kitchen table",
                            "position": [x + 0.1, y]})
    world = World.from_dict(data)
    assert object_positions(world, seed=1)["red cup"] == pytest.approx((x + 0.1, y))
    data["objects"][-1]["position"] = [x + 5.0, y]
    with pytest.raises(WorldError, match="not on the surface of 'kitchen table'"):
        World.from_dict(data)


def test_front_defaults_to_the_approach_side_and_can_be_given() -> None:
    data = World.load("apartment").to_dict()
    world = World.from_dict(data)
    table = world.placements["kitchen table"]
    ax, ay = table.approach.x - table.model.center[0], table.approach.y - table.model.center[1]
    heading = front_heading(table)
    assert math.cos(heading) * ax + math.sin(heading) * ay > 0  # faces the approach side
    for placement in data["placements"]:
        if placement["name"] == "kitchen table":
            placement["front"] = "west"
    assert front_heading(World.from_dict(data).placements["kitchen table"]) == pytest.approx(
        math.pi)
