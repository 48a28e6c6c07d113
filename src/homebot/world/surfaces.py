"""Where objects stand on their placement's surface, and which side a placement faces."""

from __future__ import annotations

import math
import random

from homebot.world.world import Placement, World

__all__ = ["FRONT_HEADINGS", "front_heading", "object_positions"]

#: the heading (radians, map frame) of each side a placement may face
FRONT_HEADINGS = {"east": 0.0, "north": math.pi / 2, "west": math.pi, "south": -math.pi / 2}
#: objects sampled onto a surface keep this far from its edge (metres)
_EDGE = 0.05
#: tries to keep sampled objects apart before accepting an overlap
_TRIES = 40


def front_heading(placement: Placement) -> float:
    """The direction a placement faces: its ``front`` side, by default the side of its
    approach pose (where the robot, and a person using it, stand)."""
    if placement.model.front is not None:
        return FRONT_HEADINGS[placement.model.front]
    cx, cy = placement.model.center
    ax, ay = placement.approach.x - cx, placement.approach.y - cy
    if ax == 0 and ay == 0:  # a spot: the robot stands on it, facing its heading
        return placement.approach.theta + math.pi
    half_w, half_d = placement.model.size[0] / 2, placement.model.size[1] / 2
    # the side whose outward normal the approach point lies along most (footprint scaled)
    if abs(ax) / half_w >= abs(ay) / half_d:
        return 0.0 if ax > 0 else math.pi
    return math.pi / 2 if ay > 0 else -math.pi / 2


def object_positions(world: World, seed: int) -> dict[str, tuple[float, float]]:
    """Every object's position on its placement: as the world file gives it, or sampled
    uniformly on the surface (kept ``_EDGE`` from its rim, apart from the objects already
    there when the surface has room) with ``random.Random(seed)``; same seed, same poses."""
    rng = random.Random(seed)
    positions: dict[str, tuple[float, float]] = {
        name: (float(obj.position[0]), float(obj.position[1]))
        for name, obj in world.objects.items() if obj.position is not None}
    for name, obj in world.objects.items():
        if obj.position is not None:
            continue
        placement = world.placements[obj.placement]
        cx, cy = placement.model.center
        half_w = max(placement.model.size[0] / 2 - _EDGE, 0.0)
        half_d = max(placement.model.size[1] / 2 - _EDGE, 0.0)
        neighbours = [positions[other] for other, o in world.objects.items()
                      if o.placement == obj.placement and other in positions]
        point = (cx, cy)
        for _ in range(_TRIES):
            point = (round(cx + rng.uniform(-half_w, half_w), 4),
                     round(cy + rng.uniform(-half_d, half_d), 4))
            if all(math.dist(point, there) >= obj.size for there in neighbours):
                break
        positions[name] = point
    return positions
