"""A person the robot guides ("follow me"), walking after it by their own rule.

Asked to follow, a person walks after the robot at a human pace along where it went: its
true trail, dropped as crumbs every ``_CRUMB`` metres (a path the robot's body fitted
through, so through open doors and never through walls or furniture), joined to where
they stand by a path they plan themselves (``Simulation.navigator``). They keep about
``gap`` metres of trail behind the robot, stop when they are that near and see it (so they
stop when it stops; round a corner or a door frame from it, or in a doorway, they come
on until they see it from clear floor), and never step within ``PERSONAL_SPACE`` of its
body. Where the robot doubles
back, the loop it drove is cut from the trail: they go straight to where it came back.

People differ (``Personality``, drawn by seed and name, ``personality_of``):

- ``STEADY``: they keep up;
- ``LAGGING``: they walk slower than the robot drives and now and then stop to look round;
- ``WANDERING``: after a few metres they walk off to a nearby spot of their own choosing
  and stay there until the robot comes back within ``HEARS_AGAIN`` metres and asks them
  to follow again; then they follow (and do not wander again).

Only the simulator moves them (``Simulation.move_person``); nothing here looks at what the
robot believes. Deterministic by the walk's seed.
"""

from __future__ import annotations

import itertools
import math
import random
from dataclasses import dataclass, field
from enum import StrEnum

from homebot.sim.simulation import Simulation

__all__ = ["HEARS_AGAIN", "PACE_LIMIT", "PERSONAL_SPACE", "GuidedWalk", "Personality",
           "personality_of"]

PACE_LIMIT = 1.2  #: m/s: nobody guided walks faster
PERSONAL_SPACE = 0.3  #: metres beyond the robot's radius that a guided person keeps clear
HEARS_AGAIN = 1.6  #: metres: a person who wandered off follows again when asked from this near


class Personality(StrEnum):
    """How a guided person follows."""

    STEADY = "steady"  #: keeps up
    LAGGING = "lagging"  #: slower, and stops to look round now and then
    WANDERING = "wandering"  #: walks off to a nearby spot once, and waits to be fetched


#: the share of guided people of each personality (``personality_of``)
SHARES: tuple[tuple[Personality, float], ...] = (
    (Personality.STEADY, 0.6), (Personality.LAGGING, 0.2), (Personality.WANDERING, 0.2))
_PACE = {Personality.STEADY: (0.7, 1.1), Personality.LAGGING: (0.3, 0.45),
         Personality.WANDERING: (0.6, 1.0)}  #: m/s, drawn per walk
_GAP = (0.9, 1.2)  #: metres of trail kept behind the robot, drawn per walk
_CRUMB = 0.1  #: metres between the points of the robot's trail
_LOOP = 0.3  #: metres: the trail coming back this near an earlier point cuts the loop
_LOOK_ROUND_RATE = 0.1  #: per second walking: chance a lagging person stops to look round
_LOOK_ROUND = (2.0, 5.0)  #: seconds they look round
_WANDER_AFTER = (2.0, 6.0)  #: metres walked before a wandering person walks off
_WANDER_REACH = (1.5, 3.0)  #: metres from where they are to the spot they walk off to
_OFF_THE_TRAIL = 0.8  #: metres the spot they walk off to keeps from the robot's trail
_WANDER_WALK = 4.5  #: metres they walk at most to get there
_WANDER_DIRECTIONS = 16
_DOORWAY = 0.9  #: metres from a door's centre within which nobody wanders off to stand
_STANDS_CLEAR_OF_DOOR = 0.6  #: metres from a door's centre: nobody stops to stand nearer
_END = 0.15  #: metres at either end of a line of sight that may touch furniture or a wall
_NOTICES = 3.0  #: metres within which someone standing turns to face the robot


def personality_of(seed: int, name: str) -> Personality:
    """The personality of ``name`` guided in the run of ``seed`` (``SHARES``)."""
    draw = random.Random(f"{seed}:{name}:personality").random()
    for personality, share in SHARES:
        if draw < share:
            return personality
        draw -= share
    return SHARES[-1][0]


@dataclass
class GuidedWalk:
    """One person following the robot (see the module docstring): made with ``start``.

    Args:
        name: who follows.
        personality: how they follow.
        path: the points still to walk to: their own way to the trail, then the trail.
        seed: their pace, gap, pauses and wandering.
    """

    name: str
    personality: Personality
    path: list[tuple[float, float]]
    seed: int = 0
    heading: float = 0.0
    finished: bool = False
    #: they walked off and stand apart (or are on their way there), not following
    wandered: bool = False
    pace: float = field(init=False)
    gap: float = field(init=False)
    walked: float = 0.0  #: metres walked following
    _wander_after: float = field(init=False)
    _looking_round_until: float = 0.0
    _rng: random.Random = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._rng = random.Random(f"{self.seed}:{self.name}:guided")
        self.pace = min(PACE_LIMIT, self._rng.uniform(*_PACE[self.personality]))
        self.gap = self._rng.uniform(*_GAP)
        self._wander_after = (self._rng.uniform(*_WANDER_AFTER)
                              if self.personality is Personality.WANDERING else math.inf)

    @classmethod
    def start(cls, sim: Simulation, name: str, personality: Personality) -> GuidedWalk:
        """``name`` sets off after the robot in ``sim``: their own way to where it stands."""
        walk = cls(name, personality, [], seed=sim.seed)
        walk.path = walk._way_to_robot(sim)
        return walk

    def asked_again(self, sim: Simulation) -> bool:
        """The robot asked them to follow again: whether they do (one who wandered off,
        when it asks from within ``HEARS_AGAIN`` metres)."""
        if not self.wandered:
            return True
        here = sim.people[self.name].position
        if math.dist(here, sim.robot_pose[:2]) > HEARS_AGAIN:
            return False
        self.wandered = False
        self._wander_after = math.inf  # once is enough
        self.path = self._way_to_robot(sim)
        sim.events.record("sim.person", person=self.name, did="follows again")
        return True

    # ------------------------------------------------------------ time passing

    def advance(self, sim: Simulation, seconds: float, robot: tuple[float, float]) -> None:
        """Let ``seconds`` pass for the person in ``sim`` (the robot's centre at ``robot``)."""
        if self.finished:
            return
        state = sim.people[self.name]
        state.got_up = True
        here = state.position
        if not self.wandered:
            self._note_trail(here, robot)
        if sim.clock.now() < self._looking_round_until:
            return
        if not self.wandered and self.walked >= self._wander_after:
            self._walk_off(sim, here)
        keep_away = sim.world.robot.radius + PERSONAL_SPACE
        if self.wandered:
            self._walk_on(sim, here, self.pace * seconds, robot, keep_away)
            if not self.path and math.dist(here, robot) <= _NOTICES:
                self.heading = _towards(here, robot)
            return
        ahead = self._trail_length(here, robot) - self.gap
        near = ahead <= 0.0 or math.dist(here, robot) <= self.gap
        if near and _in_sight(sim, here, robot) and not _in_doorway(sim, here):
            self.heading = _towards(here, robot)  # near enough: they stand and watch it
            return
        # round a corner or a door frame from it, or in a doorway, they come on
        step = self.pace * seconds if near else min(self.pace * seconds, ahead)
        moved = self._walk_on(sim, here, step, robot, keep_away)
        self.walked += moved
        if moved > 0.0 and self.personality is Personality.LAGGING and \
                self._rng.random() < _LOOK_ROUND_RATE * seconds:
            self._looking_round_until = sim.clock.now() + self._rng.uniform(*_LOOK_ROUND)
            self.heading += self._rng.uniform(-2.0, 2.0)

    def _walk_on(self, sim: Simulation, here: tuple[float, float], distance: float,
                 robot: tuple[float, float], keep_away: float) -> float:
        """Walk ``distance`` metres along the path (to the robot when it runs out), never
        within ``keep_away`` of the robot; metres walked."""
        position, left = here, distance
        points = list(self.path)
        while left > 1e-9:
            if points:
                target = points[0]
            elif not self.wandered:
                target = robot
            else:
                break
            gap = math.dist(position, target)
            if gap <= left:
                position, left = target, left - gap
                if points:
                    points.pop(0)
                else:
                    break
            else:
                position = (position[0] + left * (target[0] - position[0]) / gap,
                            position[1] + left * (target[1] - position[1]) / gap)
                left = 0.0
        if position == here or math.dist(position, robot) < min(keep_away,
                                                                  math.dist(here, robot)):
            return 0.0
        self.heading = _towards(here, position)
        self.path = points
        sim.move_person(self.name, position)
        return math.dist(here, position)

    # ------------------------------------------------------------ the trail

    def _note_trail(self, here: tuple[float, float], robot: tuple[float, float]) -> None:
        """Drop a crumb where the robot is, once it moved on from the last; a trail that
        comes back near an earlier point (or near the person) loses the loop between."""
        last = self.path[-1] if self.path else here
        if math.dist(last, robot) < _CRUMB:
            return
        if math.dist(here, robot) < _LOOP:
            self.path = [robot]
            return
        for index, point in enumerate(self.path):
            if math.dist(point, robot) < _LOOP:
                self.path = [*self.path[:index], robot]
                return
        self.path.append(robot)

    def _trail_length(self, here: tuple[float, float], robot: tuple[float, float]) -> float:
        points = [here, *self.path, robot]
        return sum(math.dist(a, b) for a, b in itertools.pairwise(points))

    def _way_to_robot(self, sim: Simulation) -> list[tuple[float, float]]:
        here = sim.people[self.name].position
        plan = sim.navigator.plan(here, sim.robot_pose[:2], sim.closed_doors())
        if plan is None:
            return []
        return [tuple(point) for point in plan.waypoints[1:-1]]  # type: ignore[misc]

    # ------------------------------------------------------------ wandering off

    def _walk_off(self, sim: Simulation, here: tuple[float, float]) -> None:
        """Choose a nearby spot off the robot's trail (in their room or through a door) and
        walk there."""
        self._wander_after = math.inf
        spots = []
        trail = [here, *self.path, sim.robot_pose[:2]]
        grid, clearance = sim.navigator.grid, sim.navigator.clearance()
        for turn in range(_WANDER_DIRECTIONS):
            angle = 2 * math.pi * turn / _WANDER_DIRECTIONS
            reach = self._rng.uniform(*_WANDER_REACH)
            spot = (here[0] + reach * math.cos(angle), here[1] + reach * math.sin(angle))
            if sim.world.room_at(*spot) is None or any(
                    math.dist(spot, door.position) < _DOORWAY
                    for door in sim.world.doors.values()):
                continue  # nobody chooses to stand about in a doorway
            cell = grid.cell_of(*spot)
            rows, columns = grid.shape
            if not (0 <= cell[0] < rows and 0 <= cell[1] < columns) or grid.blocked[cell] or \
                    clearance[cell] < PERSONAL_SPACE:
                continue
            if min(math.dist(spot, point) for point in trail) < _OFF_THE_TRAIL:
                continue
            plan = sim.navigator.plan(here, spot, sim.closed_doors())
            if plan is not None and plan.length <= _WANDER_WALK:
                spots.append([tuple(point) for point in plan.waypoints[1:]])
        if not spots:
            return
        self.path = spots[self._rng.randrange(len(spots))]  # type: ignore[assignment]
        self.wandered = True
        sim.events.record("sim.person", person=self.name, did="wandered off",
                          to=[round(v, 2) for v in self.path[-1]])


def _in_sight(sim: Simulation, here: tuple[float, float], there: tuple[float, float]) -> bool:
    """Whether no wall or furniture stands between ``here`` and ``there``."""
    grid = sim.navigator.grid
    length = math.dist(here, there)
    steps = int(length / (grid.resolution / 2))
    for index in range(1, steps):
        along = index / steps
        if _END <= along * length <= length - _END and grid.occupied[grid.cell_of(
                here[0] + along * (there[0] - here[0]), here[1] + along * (there[1] - here[1]))]:
            return False
    return True


def _in_doorway(sim: Simulation, here: tuple[float, float]) -> bool:
    return any(math.dist(here, door.position) < _STANDS_CLEAR_OF_DOOR
               for door in sim.world.doors.values())


def _towards(here: tuple[float, float], there: tuple[float, float]) -> float:
    return math.atan2(there[1] - here[1], there[0] - here[0])
