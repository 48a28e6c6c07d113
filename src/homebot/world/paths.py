"""Ways through the home: routes of rooms and doors, drivable paths, and the planner's interface.

The planning itself (A* on the occupancy grid, routed through the topological map) is
the action layer's ``homebot.navigation.Navigator``. ``PathPlanner`` is what it offers,
so that the simulator (which moves its people and its symbolic robot along such paths)
and the skills (which ask how far a place is) use a planner they are given without
importing the action layer. The composition root passes them the navigator.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from homebot.world.grid import OccupancyGrid

__all__ = ["NavigationPlan", "PathPlanner", "Route"]


@dataclass(frozen=True, slots=True)
class Route:
    """Rooms and the doors between them, in travel order."""

    rooms: tuple[str, ...]
    doors: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class NavigationPlan:
    """A path the robot can drive: waypoints, its length, and the doors it passes."""

    waypoints: tuple[tuple[float, float], ...]
    length: float
    doors: tuple[str, ...]
    route: Route

    def __bool__(self) -> bool:
        return bool(self.waypoints)


class PathPlanner(Protocol):
    """Paths in one home for one robot radius (``homebot.navigation.Navigator`` is one)."""

    @property
    def grid(self) -> OccupancyGrid:
        """The home rasterised for the robot's radius."""
        ...

    def plan(self, start: tuple[float, float], goal: tuple[float, float],
             closed_doors: frozenset[str] = frozenset()) -> NavigationPlan | None:
        """A path from ``start`` to ``goal`` avoiding shut doors, or None if there is none."""
        ...

    def plan_around(self, start: tuple[float, float], goal: tuple[float, float],
                    closed_doors: frozenset[str], obstacles: np.ndarray,
                    clearance: float, static_clearance: float | None = None,
                    near_goal: float = 0.0) -> tuple[tuple[float, float], ...] | None:
        """Waypoints of a path keeping ``clearance`` from ``obstacles`` ((n, 2) map points)."""
        ...

    def distance(self, start: tuple[float, float], goal: tuple[float, float],
                 closed_doors: frozenset[str] = frozenset()) -> float:
        """Path length from start to goal (infinite when unreachable)."""
        ...

    def clearance(self) -> np.ndarray:
        """Metres from each cell centre of ``grid`` to the nearest wall or furniture cell."""
        ...
