"""Where things are for the robot: poses of placements, rooms, people and doors."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from scipy import ndimage

from homebot.geometry import Pose
from homebot.robot import PersonPercept
from homebot.skills.skill import SkillContext

__all__ = [
    "HANDING_REACH",
    "OPERATOR",
    "near",
    "people_in_view",
    "person_name",
    "point_goal",
    "pose_near_point",
    "resolve_target",
    "room_centre",
    "sees_person_nearby",
    "target_label",
]

OPERATOR = "operator"  #: how a task names the person who gave the command

#: metres within which the robot hands a person something (arm's length and a step)
HANDING_REACH = 1.5
# How far from a person the robot stops to talk or hand over, in metres.
_PERSON_DISTANCE = 0.9
# The farthest from a person the robot stands to talk or hand over (within arm's and voice's reach).
_PERSON_REACH_LIMIT = 1.8
# How much free floor the robot keeps round itself in the middle of a room, metres.
_ROOM_MARGIN = 0.15


def person_name(context: SkillContext, name: str | Mapping[str, Any] | None) -> str | None:
    """A person's name: ``operator`` becomes the world's operator, None the person last found.

    A description (``{name: ...}``, as ``find_person`` takes) stands for the name in it,
    or for the person last found when it names nobody.
    """
    if isinstance(name, Mapping):
        name = name.get("name")
    if name is None:
        found = context.bindings.get("person")
        return str(found) if found else None
    if name == OPERATOR:
        operator = context.world.model.operator
        return operator
    return name if name in context.beliefs.person_at else None


def room_centre(context: SkillContext, room: str) -> tuple[float, float]:
    """Where the robot stands to be in the middle of ``room``: the free floor nearest its
    centroid, with a margin round the furniture (a kitchen's centroid may lie under
    its table)."""
    centre = context.world.room_polygons[room].centroid
    grid = context.navigator.grid
    margin = math.ceil(_ROOM_MARGIN / grid.resolution)
    crowded = ndimage.binary_dilation(grid.blocked, iterations=margin) if margin else grid.blocked
    cell = grid.nearest_free(crowded.ravel(), *grid.cell_of(centre.x, centre.y))
    if cell is None:
        return (centre.x, centre.y)
    point = grid.center_of(*cell)
    return point if context.world.room_at(*point) == room else (centre.x, centre.y)


def pose_near_point(context: SkillContext, point: tuple[float, float],
                    distance: float = _PERSON_DISTANCE) -> Pose:
    """A free pose ``distance`` from ``point``, facing it, on the side nearest the robot.

    Someone lying on a bed or sitting deep in a sofa may have no free floor that
    near: then the ring is widened, up to ``_PERSON_REACH_LIMIT``.
    """
    grid = context.navigator.grid
    here = context.robot.pose()
    mask = grid.blocked.ravel()
    columns = grid.shape[1]
    ring = distance
    while ring <= _PERSON_REACH_LIMIT:
        candidates = []
        for step in range(12):
            angle = step * math.pi / 6
            x, y = point[0] + ring * math.cos(angle), point[1] + ring * math.sin(angle)
            row, column = grid.cell_of(x, y)
            if context.world.room_at(x, y) is None or mask[row * columns + column]:
                continue
            candidates.append((math.dist((x, y), here.xy()), x, y))
        if candidates:
            _, x, y = min(candidates)
            return Pose(x, y, math.atan2(point[1] - y, point[0] - x))
        ring += 0.3
    return Pose(point[0], point[1], 0.0)


def point_goal(target: Any) -> tuple[float, float] | None:
    """(x, y) of a point goal, ``[x, y]`` or ``{x: X, y: Y}`` in the map frame; else None.

    Raises ``ValueError`` (saying what is wrong) for a list or mapping that is not a
    point of two finite numbers.
    """
    if isinstance(target, Mapping):
        if set(map(str, target)) != {"x", "y"}:
            raise ValueError(f"a point is {{x: X, y: Y}}, not keys {sorted(map(str, target))}")
        values = [target["x"], target["y"]]
    elif isinstance(target, (list, tuple)):
        if len(target) != 2:
            raise ValueError(f"a point is [x, y], two numbers, not {len(target)}")
        values = list(target)
    else:
        return None
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
               for v in values):
        raise ValueError("a point's x and y are finite numbers in metres")
    return (float(values[0]), float(values[1]))


def target_label(target: Any) -> str:
    """How a target is spoken of: its name, or ``the point (x, y)``."""
    try:
        point = point_goal(target)
    except ValueError:
        point = None
    return f"the point ({point[0]:g}, {point[1]:g})" if point else str(target)


def resolve_target(context: SkillContext, target: Any) -> Pose | None:
    """The pose to drive to for a placement, room, person, ``operator`` or door name,
    or a point goal (``[x, y]`` / ``{x: X, y: Y}``, faced in the direction of travel)."""
    world = context.world
    try:
        point = point_goal(target)
    except ValueError:
        return None
    if point is not None:
        here = context.robot.pose().xy()
        return Pose(point[0], point[1], math.atan2(point[1] - here[1], point[0] - here[0]))
    target = str(target)
    if target in world.placements:
        return world.placements[target].approach
    if target in world.rooms:
        return Pose(*room_centre(context, target), 0.0)
    name = person_name(context, target)
    if name is not None and name in context.beliefs.person_at:
        return pose_near_point(context, context.beliefs.person_at[name])
    if target in world.doors:
        return world.point_before_door(target, world.doors[target].rooms[0], 0.6)
    return None


def near(context: SkillContext, pose: Pose, tolerance: float = 0.3) -> bool:
    """Whether the robot (as it localises itself) is within ``tolerance`` of ``pose``."""
    return math.dist(context.robot.pose().xy(), pose.xy()) <= tolerance


def people_in_view(context: SkillContext) -> list[PersonPercept]:
    """The people the robot sees now, with no name where it already learnt that whoever
    stands there is not the person their face says (``Beliefs.mistook``)."""
    beliefs = context.beliefs
    return [replace(seen, name=None) if seen.name and beliefs.is_mistaken(seen.name,
                                                                          seen.position)
            else seen for seen in context.robot.perceive_people()]


def sees_person_nearby(context: SkillContext, person: str, reach: float = 2.0) -> bool:
    """Look around: is ``person`` seen within ``reach`` metres? Beliefs follow what is seen."""
    here = context.robot.pose().xy()
    for seen in people_in_view(context):
        if seen.name == person and math.dist(seen.position, here) <= reach:
            context.beliefs.saw_person(person, seen.position)
            return True
    return False
