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
from homebot.world.world import Placement, World, shipped_world_names, shipped_world_path

__all__ = [
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
    "shipped_world_names",
    "shipped_world_path",
]
