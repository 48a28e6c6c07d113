"""People who walk a route of their own: an operator the robot follows, someone who goes
ahead to a room when asked, a passer-by who crosses the way.

A ``RouteWalk`` is one such walk: the places to pass, in order, and how the person walks
it. They go at their own pace along paths they plan themselves (``Simulation.navigator``,
through shut doors, which they open on reaching them), pause now and then (at a corner,
to look round), wait when the robot stands just ahead of them, and, at the end, may say
something aloud ("stop"). Only the simulator moves them (``Simulation.move_person``);
nothing here looks at what the robot believes. Deterministic by the walk's seed.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from homebot.sim.simulation import Simulation
from homebot.world import DoorState

__all__ = ["ROUND_ROBOT", "RouteWalk", "plan_route", "way_round_robot"]

_AT_DOOR = 0.7  #: metres from a shut door's centre where a person stops to open it
_OPENING = 1.5  #: seconds a person takes to open a door
_YIELD = 0.8  #: metres: the robot's centre this close ahead stops a walker...
_PASS = 0.5  #: ... when it is nearer than this to the way they walk on
_CORNER = math.radians(45.0)  #: a turn this sharp is a corner, where people may pause
_OFF_WALLS = 0.35  #: metres people keep from walls and furniture as they walk
_PATIENCE = 3.0  #: seconds a walker waits for the robot before walking round it
ROUND_ROBOT = (0.75, 0.55)  #: metres a walker going round the robot keeps from its centre


@dataclass
class RouteWalk:
    """One person walking a route (see the module docstring).

    Args:
        name: who walks.
        path: the points still to walk to, in order (map frame).
        pace: metres per second.
        pauses: seconds paused at each corner, drawn per corner from this range; a
            share ``pause_chance`` of corners gets one.
        starts_at: simulated time at which they set off.
        starts_when: and they set off only once this holds (e.g. someone else came by).
        at_end: called once when they arrive (e.g. they say "stop").
        seed: the pauses' randomness.
    """

    name: str
    path: list[tuple[float, float]]
    pace: float
    pauses: tuple[float, float] = (1.0, 4.0)
    pause_chance: float = 0.3
    starts_at: float = 0.0
    starts_when: Callable[[], bool] | None = None
    at_end: Callable[[], None] | None = None
    seed: int = 0
    heading: float = 0.0
    finished: bool = False
    _resting_until: float = 0.0
    _waiting_since: float | None = None
    _rng: random.Random = field(init=False, repr=False)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.pace) and self.pace > 0):
            raise ValueError(f"a walking pace must be a positive number of m/s, not {self.pace}")
        self._rng = random.Random(f"{self.seed}:{self.name}:route")
        self._resting_until = self.starts_at

    def advance(self, sim: Simulation, seconds: float, robot: tuple[float, float]) -> None:
        """Let ``seconds`` pass for the walker in ``sim`` (the robot's centre at ``robot``)."""
        if self.finished:
            return
        now = sim.clock.now()
        if now < self._resting_until:
            return
        if self.starts_when is not None:
            if not self.starts_when():
                return
            self.starts_when = None
        state = sim.people[self.name]
        state.got_up = True  # whoever sat or lay, walks standing
        here = state.position
        if not self.path:
            self._arrive()
            return
        target = self.path[0]
        heading = math.atan2(target[1] - here[1], target[0] - here[0])
        if self._robot_ahead(here, target, robot):
            # wait for the robot to move on; if it does not, walk round it
            if self._waiting_since is None:
                self._waiting_since = now
            elif now - self._waiting_since >= _PATIENCE:
                way = way_round_robot(sim, here, self.path, robot)
                if way is not None:
                    self.path = way
                    self._waiting_since = None
            return
        self._waiting_since = None
        door = self._shut_door_ahead(sim, here)
        if door is not None:
            sim.door_state[door] = DoorState.OPEN
            sim.events.record("sim.person", person=self.name, did="opened", door=door)
            self._resting_until = now + _OPENING
            return
        self.heading = heading
        step = self.pace * seconds
        remaining = math.dist(here, target)
        if step < remaining:
            sim.move_person(self.name, (here[0] + step * math.cos(heading),
                                        here[1] + step * math.sin(heading)))
            return
        sim.move_person(self.name, target)
        self.path.pop(0)
        if not self.path:
            self._arrive()
        elif self._corner(here, target, self.path[0]) and \
                self._rng.random() < self.pause_chance:
            self._resting_until = now + self._rng.uniform(*self.pauses)

    def _arrive(self) -> None:
        self.finished = True
        if self.at_end is not None:
            self.at_end()

    @staticmethod
    def _robot_ahead(here: tuple[float, float], target: tuple[float, float],
                     robot: tuple[float, float]) -> bool:
        """Whether walking on towards ``target`` would walk into the robot."""
        if math.dist(here, robot) >= _YIELD:
            return False
        dx, dy = target[0] - here[0], target[1] - here[1]
        length = math.hypot(dx, dy)
        if length < 1e-9:
            return False
        along = ((robot[0] - here[0]) * dx + (robot[1] - here[1]) * dy) / length
        if along <= 0.0:
            return False  # behind them
        along = min(along, length)
        closest = (here[0] + dx * along / length, here[1] + dy * along / length)
        return math.dist(closest, robot) < _PASS

    @staticmethod
    def _shut_door_ahead(sim: Simulation, here: tuple[float, float]) -> str | None:
        for name, door in sim.world.doors.items():
            if sim.door_state[name] is DoorState.CLOSED and \
                    math.dist(here, door.position) <= _AT_DOOR:
                return name
        return None

    @staticmethod
    def _corner(before: tuple[float, float], at: tuple[float, float],
                after: tuple[float, float]) -> bool:
        into = math.atan2(at[1] - before[1], at[0] - before[0])
        out = math.atan2(after[1] - at[1], after[0] - at[0])
        turn = abs(math.remainder(out - into, math.tau))
        return turn >= _CORNER


def way_round_robot(sim: Simulation, here: tuple[float, float],
                    path: list[tuple[float, float]], robot: tuple[float, float]
                    ) -> list[tuple[float, float]] | None:
    """A new way along ``path`` from ``here`` that keeps clear of the robot (roomily, else
    squeezing by), or else a step aside first to let it by; None if none."""
    for keep in ROUND_ROBOT:
        way = sim.navigator.plan_around(here, path[-1], sim.closed_doors(),
                                        np.asarray([robot]), keep)
        if way is not None:
            return list(way[1:])
    # no way round (the robot stands in the doorway they need): let it by first
    spot = sim.spot_aside(here)
    aside = None if spot is None else sim.navigator.plan_around(
        here, spot, sim.closed_doors(), np.asarray([robot]), ROUND_ROBOT[0])
    if aside is None:
        return None
    return [*aside[1:], *path]


def plan_route(sim: Simulation, start: tuple[float, float],
               places: Sequence[tuple[float, float]]) -> list[tuple[float, float]] | None:
    """The points a person walks from ``start`` through ``places`` in order, on paths they
    plan themselves (through shut doors, which they open), keeping off walls and furniture
    as people do; None when a leg has no path. A locked door is no way for anyone."""
    locked = frozenset(name for name, state in sim.door_state.items()
                       if state is DoorState.LOCKED)
    points: list[tuple[float, float]] = []
    here = start
    for place in places:
        way = sim.navigator.plan_around(here, place, locked, np.zeros((0, 2)), 0.0,
                                        static_clearance=_OFF_WALLS)
        if way is None:
            plan = sim.navigator.plan(here, place, locked)
            if plan is None:
                return None
            way = plan.waypoints
        points.extend(way[1:])
        here = place
    return points
