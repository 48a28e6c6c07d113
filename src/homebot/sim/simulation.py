"""``Simulation``: the ground truth of a running home and the disturbances that change it.

The truth (where every object is, which doors are shut, who stands where) lives
here alone. The robot sees it only through ``SimRobot``'s sensors. Every random
choice draws from one ``random.Random`` seeded at construction.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from shapely.geometry import MultiLineString
from shapely.geometry import Point as ShapelyPoint

from homebot.clock import Clock
from homebot.events import EventLog
from homebot.sim.people import Responder, ScriptedResponder
from homebot.world import (
    DisturbanceModel,
    DoorState,
    NavigationPlan,
    PathPlanner,
    PersonModel,
    PlacementKind,
    Posture,
    World,
    object_positions,
)

__all__ = ["HAND_PREFIX", "PERSON_PREFIX", "Simulation"]

HAND_PREFIX = "hand:"  #: object location held in a robot hand, e.g. ``hand:left``
PERSON_PREFIX = "person:"  #: object location given to a person, e.g. ``person:Alex``
_STEP_ASIDE = (0.8, 1.2, 1.6, 2.0)  #: metres a person letting the robot by may step
_ASIDE_DIRECTIONS = 16
_CLEAR_OF_ROBOT = 1.0  #: metres from the robot's centre a person stepping aside keeps
_ALONG_THE_WAY = 2.5  #: metres past the person that the robot's way is taken to go on
_CLEAR_OF_THE_WAY = 0.9  #: metres a person stepping aside keeps from that way
_EDGE_KEPT = 0.08  #: metres from a surface's edge that an object put on it stands at least
_SPOTS_ACROSS = 8  #: spots tried along each side of a surface when an object is put on it


@dataclass
class _PersonState:
    model: PersonModel
    position: tuple[float, float]
    room: str
    blocking_door: str | None = None
    got_up: bool = False  #: they set off walking: whatever the world file said, they stand

    @property
    def posture(self) -> Posture:
        return Posture.STANDING if self.got_up else self.model.posture


class PlanCache:
    """Navigation plans remembered by start, goal and shut doors, for one navigator.

    A plan depends on nothing else (the grid and the doors are the navigator's), so a
    robot that drives the same legs again (every fetch task starts at the same pose and
    goes to the same approach poses) gets its plan without planning. At most ``size``
    plans are kept; then it starts again.
    """

    __slots__ = ("_plans", "navigator", "size")

    def __init__(self, navigator: PathPlanner, size: int = 4096) -> None:
        self.navigator = navigator
        self.size = size
        self._plans: dict[tuple[tuple[float, float], tuple[float, float], frozenset[str]],
                          NavigationPlan | None] = {}

    def plan(self, start: tuple[float, float], goal: tuple[float, float],
             closed_doors: frozenset[str] = frozenset()) -> NavigationPlan | None:
        """``navigator.plan(start, goal, closed_doors)``, remembered."""
        key = ((float(start[0]), float(start[1])), (float(goal[0]), float(goal[1])),
               closed_doors)
        plans = self._plans
        if key in plans:
            return plans[key]
        if len(plans) >= self.size:
            plans.clear()
        found = plans[key] = self.navigator.plan(start, goal, closed_doors)
        return found

    def clear(self) -> None:
        """Forget every plan."""
        self._plans.clear()


class Simulation:
    """The simulated home: truth, clock, seeded randomness and disturbances.

    Args:
        world: the home as loaded.
        seed: seeds every random choice.
        disturbances: overrides the world's disturbance model (None: the world's).
        responder: how people answer questions (default: scripted from the world).
        navigator: plans paths in this world (``homebot.navigation.Navigator``, passed in
            by whoever builds the run: the simulator never imports the robot's algorithms),
            shared between runs to save rasterising.
        plans: remembered navigation plans of ``navigator``, shared between runs (None: a
            cache of this simulation's own).
    """

    def __init__(self, world: World, *, seed: int = 0,
                 disturbances: DisturbanceModel | None = None,
                 responder: Responder | None = None,
                 navigator: PathPlanner,
                 plans: PlanCache | None = None) -> None:
        self.world = world
        self.seed = seed
        self.random = random.Random(seed)
        self.clock = Clock()
        self.events = EventLog(self.clock.now)
        self.navigator = navigator
        self.plans = plans if plans is not None and plans.navigator is self.navigator else (
            PlanCache(self.navigator))
        self.disturbances = disturbances if disturbances is not None else world.disturbances
        self.responder: Responder = responder or ScriptedResponder()
        self.object_location: dict[str, str | None] = {
            name: obj.placement for name, obj in world.objects.items()}
        self.object_ids = {name: index for index, name in enumerate(sorted(world.objects))}
        #: where each object stands on its placement (the file's, or sampled with the seed)
        self.object_position = object_positions(world, seed)
        self._object_names = {index: name for name, index in self.object_ids.items()}
        #: where someone may have put an object: every piece of furniture
        self.furniture = [p.name for p in world.placements.values()
                          if p.model.kind is PlacementKind.FURNITURE]
        self.door_state = {name: door.state for name, door in world.doors.items()}
        #: doors someone opened wide: a leaf the world file left ajar now lies back flat
        #: against the wall
        self.leaves_swung_back: frozenset[str] = frozenset()
        self.people = {name: _PersonState(person, person.position, person.room)
                       for name, person in world.people.items()}
        start = world.robot.pose
        x, y = start.xy()
        self.robot_pose = (x, y, start.theta)
        self.trail: list[tuple[float, float]] = [(x, y)]  #: where the robot has driven
        #: keep at least this many of the latest trail points, at most twice as many (None:
        #: all), so that a long-running simulation's memory stays flat
        self.trail_keep: int | None = None
        #: every time the robot's body touched a wall, furniture or a person (embodied runs)
        self.collisions: list[dict[str, object]] = []
        self.hands: dict[str, str | None] = {hand: None for hand in world.robot.hands}
        self._looked_at: set[str] = set()
        #: objects that have been in the robot's hand: nobody moves what the robot just put
        #: down while it looks (``maybe_move_during_task``)
        self.handled: set[str] = set()
        self._apply_start_disturbances()

    # ------------------------------------------------------------ disturbances

    def _apply_start_disturbances(self) -> None:
        model = self.disturbances
        for name in sorted(self.object_location):
            draw = self.random.random()
            if draw < model.object_missing:
                self.object_location[name] = None
                self.events.record("sim.disturbance", what="object_missing", object=name)
            elif draw < model.object_missing + model.object_moved:
                self._move_object_elsewhere(name, self.furniture, "object_moved")
        for door in sorted(self.door_state):
            if self.door_state[door] is DoorState.OPEN and self.random.random() < model.door_closed:
                self.door_state[door] = DoorState.CLOSED
                self.events.record("sim.disturbance", what="door_closed", door=door)
        for door in sorted(self.world.doors):
            if self.random.random() < model.person_in_way:
                self.place_person_in_doorway(door)

    def _move_object_elsewhere(self, name: str, placements: list[str], what: str) -> None:
        current = self.object_location[name]
        choices = [p for p in placements if p != current]
        if not choices:
            return
        destination = self.random.choice(choices)
        self.put_object(name, destination)
        self.events.record("sim.disturbance", what=what, object=name, to=destination)

    def put_object(self, name: str, placement: str) -> None:
        """Someone puts ``name`` on ``placement``: on the free spot of its surface farthest
        from what already stands there (people do not stack things on each other)."""
        self.object_location[name] = placement
        where = self.world.placements.get(placement)
        if where is None:
            return
        others = [self.position_on(other, placement) for other in self.objects_on(placement)
                  if other != name]
        low_x, low_y, high_x, high_y = where.footprint.bounds
        margin = min(_EDGE_KEPT, (high_x - low_x) / 4, (high_y - low_y) / 4)
        spots = [(low_x + margin + (high_x - low_x - 2 * margin) * i / _SPOTS_ACROSS,
                  low_y + margin + (high_y - low_y - 2 * margin) * j / _SPOTS_ACROSS)
                 for i in range(_SPOTS_ACROSS + 1) for j in range(_SPOTS_ACROSS + 1)]
        spots = [spot for spot in spots if where.footprint.covers(ShapelyPoint(spot))]
        if not spots:
            return
        centre = where.model.center
        # Farthest from the others; of equally free spots, the one nearest the middle.
        self.object_position[name] = max(spots, key=lambda spot: (
            round(min((math.dist(spot, other) for other in others), default=1.0), 2),
            -math.dist(spot, centre)))

    def place_person_in_doorway(self, door: str, name: str | None = None) -> str:
        """Put someone (a visitor unless named) in a doorway; returns their name."""
        position = self.world.doors[door].position
        room = self.world.doors[door].rooms[0]
        name = name or f"visitor {len([p for p in self.people if p.startswith('visitor')]) + 1}"
        if name not in self.people:
            model = PersonModel(name=name, room=room, position=position, cooperative=True)
            self.people[name] = _PersonState(model, position, room)
        state = self.people[name]
        state.position, state.room, state.blocking_door = position, room, door
        self.events.record("sim.disturbance", what="person_in_way", door=door, person=name)
        return name

    def maybe_move_during_task(self, placement: str) -> None:
        """The first time the robot looks at a placement, someone may just have moved an object
        (not one the robot itself has held)."""
        if placement in self._looked_at:
            return
        self._looked_at.add(placement)
        here = sorted(name for name, where in self.object_location.items()
                      if where == placement and name not in self.handled)
        if here and self.random.random() < self.disturbances.object_moved_during_task:
            self._move_object_elsewhere(self.random.choice(here), self.furniture,
                                        "object_moved_during_task")

    # ------------------------------------------------------------ truth queries

    def open_wide(self, door: str) -> None:
        """Someone opens ``door`` all the way: no longer shut, and a leaf left ajar swung
        back against the wall."""
        self.door_state[door] = DoorState.OPEN
        self.leaves_swung_back |= {door}

    def closed_doors(self) -> frozenset[str]:
        """Doors that are shut or locked, or that someone stands in."""
        shut = {door for door, state in self.door_state.items() if state is not DoorState.OPEN}
        shut |= {p.blocking_door for p in self.people.values() if p.blocking_door}
        return frozenset(shut)

    def objects_on(self, placement: str) -> list[str]:
        return sorted(name for name, where in self.object_location.items() if where == placement)

    def position_on(self, name: str, placement: str) -> tuple[float, float]:
        """Where an object stands on ``placement``: its own position while that lies on the
        placement's surface, else (moved there since) the surface's centre."""
        here = self.object_position.get(name)
        where = self.world.placements[placement]
        if here is not None and where.footprint.covers(ShapelyPoint(here)):
            return here
        return (float(where.model.center[0]), float(where.model.center[1]))

    def object_by_id(self, handle: int) -> str | None:
        return self._object_names.get(handle)

    def robot_room(self) -> str | None:
        return self.world.room_at(self.robot_pose[0], self.robot_pose[1])

    def spot_aside(self, position: tuple[float, float]) -> tuple[float, float] | None:
        """Where a person at ``position`` steps to get out of the robot's way: the
        nearby spot with the most room round it, as people step into open floor, and to
        the side of the way the robot comes from, not further along it: neither on the
        line from the robot through them nor on the one it faces along, and in the room
        they stand in: a spot behind a wall is a walk round through a doorway, maybe the
        one the robot stands in (None: no free spot within reach)."""
        grid, clearance = self.navigator.grid, self.navigator.clearance()
        x, y, heading = self.robot_pose
        robot = (x, y)
        away = math.dist(robot, position)
        ahead = (position if away < 1e-6 else
                 (position[0] + _ALONG_THE_WAY * (position[0] - robot[0]) / away,
                  position[1] + _ALONG_THE_WAY * (position[1] - robot[1]) / away))
        faced = (x + (away + _ALONG_THE_WAY) * math.cos(heading),
                 y + (away + _ALONG_THE_WAY) * math.sin(heading))
        way = MultiLineString([[robot, ahead], [robot, faced]])
        room = self.world.room_at(*position)
        best: tuple[float, tuple[float, float]] | None = None
        for reach in _STEP_ASIDE:
            for turn in range(_ASIDE_DIRECTIONS):
                angle = 2 * math.pi * turn / _ASIDE_DIRECTIONS
                spot = (position[0] + reach * math.cos(angle),
                        position[1] + reach * math.sin(angle))
                if room is None or self.world.room_at(*spot) != room \
                        or self.distance_to(spot) < _CLEAR_OF_ROBOT \
                        or way.distance(ShapelyPoint(spot)) < _CLEAR_OF_THE_WAY:
                    continue
                cell = grid.cell_of(*spot)
                if grid.blocked[cell]:
                    continue
                score = min(float(clearance[cell]), 1.0) - 0.2 * reach
                if best is None or score > best[0]:
                    best = (score, spot)
        return best[1] if best else None

    def free_floor_near(self, point: tuple[float, float]) -> tuple[float, float]:
        """The free floor nearest ``point`` in its room (a room's middle may lie under its
        table: nobody stands inside furniture); ``point`` when there is none."""
        grid = self.navigator.grid
        cell = grid.nearest_free(grid.blocked.ravel(), *grid.cell_of(*point))
        if cell is None:
            return point
        spot = grid.center_of(*cell)
        return spot if self.world.room_at(*spot) == self.world.room_at(*point) else point

    def free_floor_in(self, room: str) -> tuple[float, float]:
        """The free floor nearest the middle of ``room`` (``free_floor_near``)."""
        middle = self.world.room_polygons[room].centroid
        return self.free_floor_near((middle.x, middle.y))

    def step_aside(self, name: str, door: str | None) -> bool:
        """Person ``name`` steps off the robot's way where there is room (``spot_aside``);
        one who blocks ``door`` on purpose, finding none, goes into their room. Whether
        they moved."""
        state = self.people[name]
        spot = self.spot_aside(state.position)
        if spot is None and state.blocking_door is not None and state.blocking_door == door:
            spot = self.free_floor_in(state.room)
        if spot is None:
            return False
        self.move_person(name, spot)
        return True

    def distance_to(self, point: tuple[float, float]) -> float:
        return math.dist(self.robot_pose[:2], point)

    def person_state(self, name: str) -> _PersonState | None:
        return self.people.get(name)

    def move_person(self, name: str, position: tuple[float, float]) -> None:
        """Move a person (walking, following the robot); they no longer block a door."""
        state = self.people[name]
        room = self.world.room_at(*position)
        state.position, state.blocking_door = position, None
        if room is not None:
            state.room = room
