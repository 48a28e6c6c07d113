"""People who walk about the home on their own, on seeded schedules.

Each walker goes from place to place (the approach spots of furniture), stays
a while, and sometimes carries an object off to where they go next. Walkers
keep out of the robot's way the way people do: they stop when the robot is
just ahead of them. They are the dynamic obstacles of the embodied robot.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from homebot.sim.body_tracker import lying_body_outline
from homebot.sim.guided import GuidedWalk
from homebot.sim.routes import ROUND_ROBOT, RouteWalk, way_round_robot
from homebot.sim.simulation import Simulation
from homebot.world import PlacementKind, Posture

__all__ = ["PeopleWalking", "Walker"]

_SPEED = (0.4, 0.8)  #: metres per second, drawn per walker
_DWELL = (5.0, 40.0)  #: seconds spent at a place
_CARRY_CHANCE = 0.1  #: share of departures on which an object is taken along
_LEG_SPREAD = 0.1  #: metres from a person's centre to each leg's
_BESIDE = 0.75  #: metres sideways from a placement's approach spot, where people stand
_YIELD_DISTANCE = 0.9  #: a walker waits when the robot's centre is this close ahead
_PATIENCE = 4.0  #: seconds a walker waits for the robot before walking round it
_DOORWAY = 0.9  #: metres from a door's centre within which nobody chooses to stand


@dataclass
class Walker:
    """One person's walk: the way ahead and when they set off again."""

    name: str
    speed: float
    heading: float = 0.0
    path: list[tuple[float, float]] = field(default_factory=list)
    destination: str | None = None
    at_place: str | None = None
    leaves_at: float = 0.0
    carrying: str | None = None
    waiting_since: float | None = None  #: when the walker stopped for the robot


class PeopleWalking:
    """Moves the chosen people of a simulation as time passes.

    Args:
        simulation: the home; its people move in its truth.
        names: who walks (people standing in a doorway for a disturbance never do).
        rng: the schedules' randomness.
    """

    def __init__(self, simulation: Simulation, names: list[str], rng: random.Random) -> None:
        self.sim = simulation
        self.rng = rng
        self.places = sorted(p.name for p in simulation.world.placements.values()
                             if p.model.kind is PlacementKind.FURNITURE)
        self.walkers = [Walker(name, rng.uniform(*_SPEED),
                               leaves_at=simulation.clock.now() + rng.uniform(0.0, _DWELL[1]))
                        for name in names]
        self._outlines: dict[tuple[str, tuple[float, float]],
                             list[tuple[float, float]] | None] = {}
        #: people walking a route of their own (an operator, someone sent ahead) or after
        #: the robot (someone guided), by name
        self.routes: dict[str, RouteWalk | GuidedWalk] = {}

    def walk_route(self, walk: RouteWalk | GuidedWalk) -> None:
        """Have ``walk.name`` walk ``walk`` (instead of any schedule or earlier route)."""
        if walk.name not in self.sim.people:
            raise KeyError(f"nobody called {walk.name!r} is in the home")
        self.routes[walk.name] = walk

    def legs(self) -> list[tuple[float, float]]:
        """Where every person's two legs are (walkers and those standing still)."""
        return [leg for _, leg in self.named_legs()]

    def named_legs(self) -> list[tuple[str, tuple[float, float]]]:
        """Each leg's centre with whose it is: two a person, across their walking direction;
        someone lying on the floor is a row of them along the body, someone lying on a bed
        none."""
        headings = {walker.name: walker.heading for walker in self.walkers}
        headings.update((name, walk.heading) for name, walk in self.routes.items())
        legs: list[tuple[str, tuple[float, float]]] = []
        for name, state in sorted(self.sim.people.items()):
            lying = self._lying_outline(name)
            if lying is not None:
                legs.extend((name, point) for point in lying)
                continue
            across = headings.get(name, 0.0) + math.pi / 2
            x, y = state.position
            for side in (-1, 1):
                legs.append((name, (x + side * _LEG_SPREAD * math.cos(across),
                                    y + side * _LEG_SPREAD * math.sin(across))))
        return legs

    def _lying_outline(self, name: str) -> list[tuple[float, float]] | None:
        """``lying_body_outline`` of ``name`` as they are now; kept while they lie still
        (every laser sweep asks, and finding the bed under them is slow)."""
        state = self.sim.people[name]
        if state.posture is not Posture.LYING:
            return None
        key = (name, state.position)
        if key not in self._outlines:
            self._outlines[key] = lying_body_outline(self.sim.world, name, state.model,
                                                     state.posture, state.position,
                                                     self.facing(name))
        return self._outlines[key]

    def facing(self, name: str) -> float:
        """Which way a person faces: where they walk; having walked a route, the robot;
        else the middle of their room."""
        walk = self.routes.get(name)
        if walk is not None and not walk.finished:
            return walk.heading
        if walk is not None:  # arrived: they turn to the robot that came along
            x, y = self.sim.people[name].position
            robot = self.sim.robot_pose
            return math.atan2(robot[1] - y, robot[0] - x)
        walker = next((walker for walker in self.walkers if walker.name == name), None)
        if walker is not None:
            return walker.heading
        state = self.sim.people[name]
        middle = self.sim.world.room_polygons[state.room].centroid
        return math.atan2(middle.y - state.position[1], middle.x - state.position[0])

    def advance(self, seconds: float, robot: tuple[float, float], keep_away: float) -> None:
        """Let ``seconds`` pass for every walker; nobody steps within ``keep_away`` of the robot."""
        now = self.sim.clock.now()
        for walk in self.routes.values():
            walk.advance(self.sim, seconds, robot)
        for walker in self.walkers:
            state = self.sim.people.get(walker.name)
            if state is None or state.blocking_door is not None or walker.name in self.routes:
                continue
            if not walker.path:
                if now >= walker.leaves_at:
                    self._set_off(walker, state.position)
                continue
            self._walk(walker, state.position, seconds, robot, keep_away)

    def _set_off(self, walker: Walker, here: tuple[float, float]) -> None:
        sim = self.sim
        destination = self.rng.choice(self.places)
        goal = self._spot_beside(destination)
        plan = sim.navigator.plan(here, goal, sim.closed_doors()) if goal else None
        if plan is None or plan.length < 0.5:
            walker.leaves_at = sim.clock.now() + self.rng.uniform(*_DWELL)
            return
        walker.path = list(plan.waypoints[1:])
        walker.destination = destination
        sim.people[walker.name].got_up = True
        origin, walker.at_place = walker.at_place, None
        if origin is not None and self.rng.random() < _CARRY_CHANCE:
            objects = sim.objects_on(origin)
            if objects:
                walker.carrying = self.rng.choice(objects)
                sim.object_location[walker.carrying] = f"person:{walker.name}"
                sim.events.record("sim.disturbance", what="object_carried",
                                  object=walker.carrying, person=walker.name, origin=origin)

    def _walk(self, walker: Walker, here: tuple[float, float], seconds: float,
              robot: tuple[float, float], keep_away: float) -> None:
        target = walker.path[0]
        heading = math.atan2(target[1] - here[1], target[0] - here[0])
        to_robot = (robot[0] - here[0], robot[1] - here[1])
        ahead = to_robot[0] * math.cos(heading) + to_robot[1] * math.sin(heading)
        beside = abs(to_robot[1] * math.cos(heading) - to_robot[0] * math.sin(heading))
        if math.hypot(*to_robot) < _YIELD_DISTANCE and ahead > -0.1 and beside < ROUND_ROBOT[0]:
            # The robot is in the way: wait for it to pass, and if it does not, go round it
            # (a robot waiting for the person to move would otherwise wait for ever).
            now = self.sim.clock.now()
            if walker.waiting_since is None:
                walker.waiting_since = now
            elif now - walker.waiting_since >= _PATIENCE and self._go_round(walker, here, robot):
                walker.waiting_since = None
            return
        walker.waiting_since = None
        walker.heading = heading
        step = walker.speed * seconds
        remaining = math.dist(here, target)
        if step < remaining:
            position = (here[0] + step * math.cos(heading), here[1] + step * math.sin(heading))
        else:
            position = target
        # Nobody steps nearer than ``keep_away`` to the robot; someone already that near
        # (the robot came up to them) may still step away from it.
        if math.dist(position, robot) < min(keep_away, math.dist(here, robot)):
            return
        if position == target:
            walker.path.pop(0)
        self.sim.move_person(walker.name, position)
        if not walker.path:
            self._arrive(walker)

    def _go_round(self, walker: Walker, here: tuple[float, float],
                  robot: tuple[float, float]) -> bool:
        """A new way to the walker's goal that keeps clear of the robot, or else a step
        aside to let the robot by; False if neither."""
        way = way_round_robot(self.sim, here, walker.path, robot)
        if way is None:
            return False
        walker.path = way
        return True

    def _arrive(self, walker: Walker) -> None:
        sim = self.sim
        walker.leaves_at = sim.clock.now() + self.rng.uniform(*_DWELL)
        walker.at_place = walker.destination
        if walker.carrying is not None and walker.destination is not None:
            sim.put_object(walker.carrying, walker.destination)
            sim.events.record("sim.disturbance", what="object_moved", object=walker.carrying,
                              to=walker.destination, person=walker.name)
            walker.carrying = None

    def _spot_beside(self, placement: str) -> tuple[float, float] | None:
        """Where a person stands at a placement: beside the robot's approach spot, not on it."""
        sim = self.sim
        approach = sim.world.placements[placement].approach
        x, y, theta = approach.x, approach.y, approach.theta
        grid = sim.navigator.grid
        for side in (1, -1):
            spot = (x + side * _BESIDE * math.cos(theta + math.pi / 2),
                    y + side * _BESIDE * math.sin(theta + math.pi / 2))
            in_doorway = any(math.dist(spot, door.position) < _DOORWAY
                             for door in sim.world.doors.values())
            if (sim.world.room_at(*spot) is not None and not in_doorway
                    and not grid.blocked[grid.cell_of(*spot)]):
                return spot
        return None
