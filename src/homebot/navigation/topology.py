"""The topological map (CAESAR §2.3.2): rooms and doors as places, routed with A*."""

from __future__ import annotations

import heapq
import math

from homebot.world import Route, World

__all__ = ["TopologicalMap"]


class TopologicalMap:
    """A graph whose nodes are rooms and whose edges are doors.

    The cost of going through a door is the distance from the previous door (or
    the room's centre) to it, so the route prefers short ways round.
    """

    def __init__(self, world: World) -> None:
        self._door_positions = {name: door.position for name, door in world.doors.items()}
        self._centres = {name: (polygon.centroid.x, polygon.centroid.y)
                         for name, polygon in world.room_polygons.items()}
        self._edges: dict[str, list[tuple[str, str]]] = {room: [] for room in world.rooms}
        for door in world.doors.values():
            first, second = door.rooms
            self._edges[first].append((door.name, second))
            self._edges[second].append((door.name, first))

    def doors_of(self, room: str) -> list[str]:
        """The doors of a room."""
        return [door for door, _ in self._edges[room]]

    def route(self, start_room: str, goal_room: str,
              closed_doors: frozenset[str] = frozenset(),
              start: tuple[float, float] | None = None,
              goal: tuple[float, float] | None = None) -> Route | None:
        """The shortest sequence of rooms and doors from one room to another, or None."""
        start_point = start or self._centres[start_room]
        goal_point = goal or self._centres[goal_room]
        # A state is (room, door entered by); the door's position is where the robot stands.
        frontier: list[tuple[float, float, str, tuple[str, ...], tuple[str, ...],
                             tuple[float, float]]] = [
            (math.dist(start_point, goal_point), 0.0, start_room, (start_room,), (), start_point)
        ]
        settled: set[tuple[str, tuple[float, float]]] = set()
        while frontier:
            _, cost, room, rooms, doors, here = heapq.heappop(frontier)
            if room == goal_room:
                return Route(rooms, doors)
            if (room, here) in settled:
                continue
            settled.add((room, here))
            for door, neighbour in self._edges[room]:
                if door in closed_doors or door in doors:
                    continue
                there = self._door_positions[door]
                new_cost = cost + math.dist(here, there)
                estimate = new_cost + math.dist(there, goal_point)
                heapq.heappush(frontier, (estimate, new_cost, neighbour, (*rooms, neighbour),
                                          (*doors, door), there))
        return None
