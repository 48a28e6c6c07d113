"""The home as data: rooms, doors, placements, objects, people and the robot."""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.lazy import lazy_exports

if TYPE_CHECKING:
    from homebot.world.catalogue import (
        CATEGORY_DEFAULTS,
        CatalogueEntry,
        CategoryDefaults,
        catalogue_entry,
        defaults_for,
        object_catalogue,
        surface_height,
    )
    from homebot.world.grid import OccupancyGrid
    from homebot.world.model import (
        COLOUR_PALETTE,
        LEG_GARMENTS,
        Colour,
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
        Shape,
        WorldModel,
    )
    from homebot.world.paths import NavigationPlan, PathPlanner, Route
    from homebot.world.shipped import shipped_world_names, shipped_world_path, world_file
    from homebot.world.surfaces import FRONT_HEADINGS, front_heading, object_positions
    from homebot.world.world import Placement, World

__all__ = [
    "CATEGORY_DEFAULTS",
    "COLOUR_PALETTE",
    "FRONT_HEADINGS",
    "LEG_GARMENTS",
    "CatalogueEntry",
    "CategoryDefaults",
    "Colour",
    "DisturbanceModel",
    "DoorModel",
    "DoorState",
    "Gesture",
    "LaserModel",
    "NavigationPlan",
    "ObjectCategoryModel",
    "ObjectModel",
    "OccupancyGrid",
    "PathPlanner",
    "PersonModel",
    "Placement",
    "PlacementKind",
    "PlacementModel",
    "Posture",
    "RobotModel",
    "RoomModel",
    "Route",
    "Shape",
    "World",
    "WorldModel",
    "catalogue_entry",
    "defaults_for",
    "front_heading",
    "object_catalogue",
    "object_positions",
    "shipped_world_names",
    "shipped_world_path",
    "surface_height",
    "world_file",
]

__getattr__ = lazy_exports(globals())
