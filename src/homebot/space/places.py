"""Referring to furniture: "the table near the couch", "the chair behind the sofa".

``resolve_place(world, wanted, modifiers, viewer)`` resolves a placement category or
name among the world's placements, with the relations read in the frame of the room
the candidates share (the world's when they are in several rooms). Relata are
placements (by name or category), doors (by name, or ``door``) and objects; a piece
of furniture is an intrinsic relatum: "behind the couch" is the side away from
where the couch faces (its ``front``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from homebot.space.frames import frames_of
from homebot.space.referring import Modifier, Resolution, Scene, resolve
from homebot.world import PlacementKind, World, front_heading, object_positions

__all__ = ["place_scene", "resolve_place"]


def place_scene(world: World, viewer: tuple[float, float], scale: float,
                positions: Mapping[str, tuple[float, float]] | None = None) -> Scene:
    """Every placement (its centre), door and object (``positions``) as one scene."""
    points: dict[str, tuple[float, float]] = {}
    categories: dict[str, str] = {}
    fronts: dict[str, float] = {}
    for name, placement in world.placements.items():
        points[name] = (float(placement.model.center[0]), float(placement.model.center[1]))
        categories[name] = placement.category
        if placement.model.kind is PlacementKind.FURNITURE:
            fronts[name] = front_heading(placement)
    for name, door in world.doors.items():
        points[name] = (float(door.position[0]), float(door.position[1]))
        categories[name] = "door"
    for name, point in (positions or {}).items():
        points.setdefault(name, point)
        categories.setdefault(name, world.objects[name].category)
    return Scene(points, categories, scale, viewer, None, fronts)


def resolve_place(world: World, wanted: str, modifiers: Sequence[Modifier],
                  viewer: tuple[float, float], seed: int = 0) -> Resolution:
    """The placement ``wanted`` (a category or name) the modifiers fit best, or a question."""
    candidates = [name for name, placement in world.placements.items()
                  if wanted in (name, placement.category)]
    rooms = {world.placements[name].room for name in candidates}
    positions = object_positions(world, seed)
    frames = frames_of(world, positions)
    scale = frames[next(iter(rooms))].scale if len(rooms) == 1 else frames["world"].scale
    scene = place_scene(world, viewer, scale, positions)
    return resolve(candidates, modifiers, scene, noun=wanted)
