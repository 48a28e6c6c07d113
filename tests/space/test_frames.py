"""Frames nest world → room → furniture → object; relations are read in the common one."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from homebot.errors import WorldError
from homebot.space.frames import Frame, frames_of
from homebot.space.relations import scene_relations
from homebot.world import World, object_positions

coordinates = st.floats(min_value=-20, max_value=20, allow_nan=False)


@given(coordinates, coordinates, st.floats(min_value=-4, max_value=4))
def test_local_and_map_coordinates_are_inverse(x: float, y: float, front: float) -> None:
    frame = Frame("table", "furniture", (1.0, 2.0), front, 1.4)
    back = frame.to_map(frame.to_local((x, y)))
    assert back == pytest.approx((x, y), abs=1e-9)


def test_apartment_frames_nest_and_scale() -> None:
    world = World.load("apartment")
    frames = frames_of(world, object_positions(world, seed=3))
    chain = [frame.kind for frame in frames.chain("cup")]
    assert chain == ["object", "furniture", "room", "world"]
    table, kitchen = frames["kitchen table"], frames["kitchen"]
    assert table.scale < kitchen.scale < frames["world"].scale
    assert frames.common("cup", "spoon").kind in ("furniture", "room")
    assert frames.common("cup", "kitchen table").name == "kitchen"
    with pytest.raises(WorldError, match="no frame"):
        frames["garage"]


def test_scene_relations_name_dist_and_orient() -> None:
    relations = scene_relations({"plate": (0.0, 0.0), "cup": (0.1, 0.0), "bowl": (1.3, 0.0)},
                                scale=math.hypot(1.2, 0.8), front=0.0)
    assert relations.dist("plate", "cup") == "close"
    assert relations.dist("plate", "bowl") == "very_far"
    assert relations.orient("plate", "cup") == "front"
    assert relations.orient("cup", "plate") == "back"
