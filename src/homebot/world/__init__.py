"""The home as data: rooms, doors, placements, objects, people and the robot."""

from homebot.world.model import (
    DisturbanceModel,
    DoorModel,
    DoorState,
    Gesture,
    LaserModel,
    ObjectCategoryModel,
    ObjectModel,
    PersonModel,
    PlacementKind,
    PlacementModel,
    Posture,
    RobotModel,
    RoomModel,
    WorldModel,
)
from homebot.world.surfaces import FRONT_HEADINGS, front_heading, object_positions
from homebot.world.world import Placement, World, shipped_world_names, shipped_world_path

__all__ = [
    "FRONT_HEADINGS",
    "DisturbanceModel",
    "DoorModel",
    "DoorState",
    "Gesture",
    "LaserModel",
    "ObjectCategoryModel",
    "ObjectModel",
    "PersonModel",
    "Placement",
    "PlacementKind",
    "PlacementModel",
    "Posture",
    "RobotModel",
    "RoomModel",
    "World",
    "WorldModel",
    "front_heading",
    "object_positions",
    "shipped_world_names",
    "shipped_world_path",
]
