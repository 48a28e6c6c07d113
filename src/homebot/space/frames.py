"""Frames of reference: world → room → furniture → object, each with a scale and a front.

As in CAESAR (Fig. 11), every frame has an origin, a front side (a heading in the map
frame, REP 103) and a maximum distance that scales the qualitative distances read in
it. Frames nest: an object on the kitchen table is in the table's frame, which is in
the kitchen's, which is in the world's. A relation between two things is read in
the smallest frame holding both (their nearest common ancestor): two cups on a
table are "close" by the table's measure, the robot and the table by the kitchen's.

- world: the bounding box of all rooms; front +x; scale its diagonal;
- room: its polygon's centroid; front +x; scale its bounding-box diagonal;
- furniture (a placement): its centre; front the side it faces
  (``homebot.world.front_heading``); scale its footprint's diagonal;
- object: its position on the surface; front that of its placement; scale four
  times its size (the frame of "right next to it").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from homebot.errors import WorldError
from homebot.geometry import Pose
from homebot.world import World, front_heading

__all__ = ["Frame", "FrameKind", "Frames", "frames_of"]

FrameKind = str  #: "world", "room", "furniture" or "object"
_OBJECT_SCALE = 4.0


@dataclass(frozen=True, slots=True)
class Frame:
    """One frame: where it is, which way its front faces, its scale and its parent."""

    name: str
    kind: FrameKind
    origin: tuple[float, float]
    front: float  #: heading of the front side, radians in the map frame
    scale: float  #: maximum distance: qualitative distances are read as d / scale
    parent: str | None = None

    def pose(self) -> Pose:
        """The frame as a map pose: its origin, heading towards its front."""
        return Pose(self.origin[0], self.origin[1], self.front)

    def to_local(self, point: tuple[float, float]) -> tuple[float, float]:
        """A map point in this frame: x towards the front, y to the frame's left."""
        return Pose(point[0], point[1]).relative_to(self.pose()).xy()

    def to_map(self, point: tuple[float, float]) -> tuple[float, float]:
        """A point of this frame in the map frame (``to_local`` undone)."""
        return self.pose().apply(point[0], point[1])


class Frames:
    """The nested frames of a home, by name (placements and objects share the world's names)."""

    def __init__(self, frames: Mapping[str, Frame]) -> None:
        self.frames = dict(frames)

    def __getitem__(self, name: str) -> Frame:
        found = self.frames.get(name)
        if found is None:
            raise WorldError(f"no frame of reference '{name}'; frames are the world, its "
                             "rooms, placements and objects")
        return found

    def __contains__(self, name: object) -> bool:
        return name in self.frames

    def chain(self, name: str) -> list[Frame]:
        """The frame and its ancestors, innermost first, ending with the world."""
        chain = [self[name]]
        while chain[-1].parent is not None:
            chain.append(self[chain[-1].parent])
        return chain

    def common(self, first: str, second: str) -> Frame:
        """The smallest frame holding both: the one relations between them are read in.

        Each thing's own frame is left out: a cup is not read in its own frame."""
        outer = {frame.name for frame in self.chain(first)[1:]}
        for frame in self.chain(second)[1:]:
            if frame.name in outer:
                return frame
        return self.chain(first)[-1]


def frames_of(world: World, positions: Mapping[str, tuple[float, float]]) -> Frames:
    """The frames of ``world`` with objects at ``positions`` (``object_positions``)."""
    min_x, min_y, max_x, max_y = world.bounds()
    frames = {"world": Frame("world", "world", ((min_x + max_x) / 2, (min_y + max_y) / 2), 0.0,
                             math.hypot(max_x - min_x, max_y - min_y))}
    for name, polygon in world.room_polygons.items():
        x0, y0, x1, y1 = polygon.bounds
        frames[name] = Frame(name, "room", (polygon.centroid.x, polygon.centroid.y), 0.0,
                             math.hypot(x1 - x0, y1 - y0), "world")
    for name, placement in world.placements.items():
        width, depth = placement.model.size
        frames[name] = Frame(name, "furniture", placement.model.center, front_heading(placement),
                             math.hypot(width, depth), placement.room)
    for name, obj in world.objects.items():
        if name in positions:
            parent = frames[obj.placement]
            frames[name] = Frame(name, "object", positions[name], parent.front,
                                 _OBJECT_SCALE * obj.size, obj.placement)
    return Frames(frames)
