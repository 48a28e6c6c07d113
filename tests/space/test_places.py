"""Referring to furniture in the room's (or the world's) frame; furniture is read intrinsically."""

from __future__ import annotations

from homebot.space.places import resolve_place
from homebot.space.referring import split_spatial
from homebot.world import World


def _said(world: World, text: str, viewer: tuple[float, float]) -> str | None:
    noun = text.split()[1]
    return resolve_place(world, noun, split_spatial(text)[1], viewer).referent


def test_tables_of_the_apartment_by_what_they_are_near() -> None:
    world = World.load("apartment")
    here = world.robot.pose.xy()
    assert _said(world, "the table close to the bed", here) == "bedside table"
    assert _said(world, "the table near the fridge", here) == "kitchen table"
    # the coffee table and the side table are about as near the couch: the robot asks
    answer = resolve_place(world, "table", split_spatial("the table near the couch")[1], here)
    assert answer.referent is None and "coffee table" in (answer.question or "")


def _lounge() -> World:
    return World.from_dict({
        "name": "lounge", "rooms": [{"name": "lounge", "polygon": [[0, 0], [6, 0], [6, 6],
                                                                   [0, 6]]}],
        "placements": [
            {"name": "sofa", "category": "sofa", "room": "lounge", "center": [3, 3],
             "size": [2.0, 0.8], "front": "north", "approach": [3, 4.2, -1.57]},
            {"name": "blue chair", "category": "chair", "room": "lounge", "center": [3, 1.8],
             "size": [0.5, 0.5], "approach": [4, 1.8, 3.14]},
            {"name": "red chair", "category": "chair", "room": "lounge", "center": [3, 4.8],
             "size": [0.5, 0.5], "approach": [4, 4.8, 3.14]},
        ],
        "robot": {"pose": [1.0, 1.0, 0.0]},
    })


def test_behind_the_sofa_is_away_from_its_front_wherever_the_viewer_stands() -> None:
    world = _lounge()
    for viewer in ((3.0, 0.5), (3.0, 5.5)):  # south of everything, then north
        assert _said(world, "the chair behind the sofa", viewer) == "blue chair"
        assert _said(world, "the chair in front of the sofa", viewer) == "red chair"
