"""Where a door's leaf swings, and the placements' approach spots it covers.

A leaf turns on its hinge from shut (across the doorway) to where the world file leaves it
(``opening``). A robot standing on a placement's approach spot within that sweep either
cannot stand there (the leaf is in the way) or stands where the door cannot be shut or
opened; ``world check`` warns of it, naming the placement and what to move.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from shapely.geometry import Point, Polygon

if TYPE_CHECKING:
    from homebot.world.world import World

__all__ = ["approaches_in_swings", "door_swing"]

_ARC_STEPS = 16  #: straight pieces the swept arc is drawn with
_LEAF_HALF_THICKNESS = 0.02  #: metres: half a leaf's thickness, round the swept area


def door_swing(world: World, door: str) -> Polygon | None:
    """The floor a door's leaf sweeps from shut to its ``opening``, as the world file has
    its hinge and swing; None for a door with no leaf drawn (no ``opening``)."""
    model = world.doors[door]
    if model.opening is None:
        return None
    hinge, _ = world.door_leaf_turned(door, 0.0)
    arc = []
    for angle in np.linspace(0.0, math.radians(model.opening), _ARC_STEPS + 1):
        _, (dx, dy) = world.door_leaf_turned(door, float(angle))
        arc.append((hinge[0] + model.width * dx, hinge[1] + model.width * dy))
    swing: Polygon = Polygon([hinge, *arc]).buffer(_LEAF_HALF_THICKNESS)
    return swing


def approaches_in_swings(world: World) -> list[tuple[int, str]]:
    """(index of the placement in the world file, what to do) for each placement whose
    approach spot a door's leaf sweeps over: the robot's disc standing there would meet it."""
    radius = world.model.robot.radius
    found: list[tuple[int, str]] = []
    for door in world.doors.values():
        swing = door_swing(world, door.name)
        if swing is None:
            continue
        for index, model in enumerate(world.model.placements):
            placement = world.placements.get(model.name)
            if placement is None:
                continue
            spot = Point(placement.approach.x, placement.approach.y)
            if swing.distance(spot) >= radius:
                continue
            x, y = placement.approach.xy()
            found.append((index, (
                f"the {door.name}'s leaf ({door.opening:g} degrees open) swings over the spot "
                f"({x:.2f}, {y:.2f}) the robot reaches the {model.name} from: move the "
                f"{model.name} away from the door, or give the door another hinge or "
                f"swings_into")))
    return found
