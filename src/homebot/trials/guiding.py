"""Guiding a person to a place (RoboCup@Home's guiding; Cosero §8.2): the robot asks someone
to follow it and leads them through the home; they follow by their own rule.

One episode, in the embodied fidelity, seeded:

- someone cooperative (one of the home's people) stands in free floor, the robot
  ``_IN_FRONT`` metres in front of them, facing them; the robot is told where it starts
  and that it has just found them;
- the goal is a piece of furniture in another room, 6–20 m of driving away through at
  least one door (all on the way open);
- asked to follow, the person walks after the robot by their own rule
  (``homebot.sim.guided``): by seed, steady, lagging (slower than the robot, stopping
  to look round) or wandering off once to a nearby spot, where they wait to be fetched.

The robot (built by the caller, ``homebot.app.guiding``) runs its Guide skill. The
referee reads only the simulator's truth: the episode succeeds when, at the end, the
person stands within ``GOAL_REACH`` metres of the goal (the robot's approach pose of the
furniture), within ``time_limit`` seconds, and the robot touched nobody and nothing. What
the robot believed (its skill's verdict) is reported beside it, never counted.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.guided import Personality, personality_of
from homebot.trials.arena import free_floor
from homebot.world import DoorState, PlacementKind, World

__all__ = ["GOAL_REACH", "ROUTE_LENGTH", "GuideArena", "GuideEpisode", "arranged_arena",
           "guide_arena"]

GOAL_REACH = 1.5  #: metres from the goal within which the person must end
ROUTE_LENGTH = (6.0, 20.0)  #: metres the robot drives from the start to the goal
_TIME_BASE, _TIME_PER_METRE = 90.0, 8.0  #: seconds the episode may take: base + per metre
_IN_FRONT = 1.2  #: metres from the person to the robot at the start
_CLEAR = 0.5  #: metres of free floor round the person's start
_ROOM_AROUND = 1.5  #: metres round the start where nobody else stands


@dataclass
class GuideEpisode:
    """One guiding run and the referee's verdict (truth only)."""

    seed: int
    world: str
    person: str = ""
    personality: str = ""
    goal: str = ""
    route_length: float = 0.0
    doors: int = 0
    success: bool = False
    end_distance: float | None = None  #: metres from the person to the goal at the end
    at_goal: bool = False  #: they ended within ``GOAL_REACH`` of it (in time or not)
    in_time: bool = False
    robot_verdict: str = ""  #: the Guide skill's status (what the robot believes)
    wandered_off: int = 0  #: times the person walked off (truth)
    fetched: int = 0  #: times they followed again after being asked from near (truth)
    noticed: int = 0  #: times the robot said it lost them (``robot.guide_lost``)
    waited: int = 0  #: times the robot waited for them (``robot.guide_waiting``)
    collisions: list[dict[str, object]] = field(default_factory=list)
    person_collisions: int = 0  #: touches of the guided person
    nearest: float = 0.0  #: metres: the nearest the robot's centre came to the person
    fastest: float = 0.0  #: m/s: the person's fastest move from one tick to the next
    sim_seconds: float = 0.0
    time_limit: float = 0.0
    wall_seconds: float = 0.0
    skipped: str | None = None  #: why no episode could be set up

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


class GuideArena:
    """One guiding episode's arena and referee (see the module docstring): set up with
    ``guide_arena``; ``start`` watches the truth in the robot's body; ``judge`` gives the
    verdict once the robot's skill ended."""

    def __init__(self, sim: Simulation, person: str, personality: Personality, goal: str,
                 goal_pose: Pose, robot_pose: Pose, route_length: float, doors: int) -> None:
        self.sim, self.person, self.goal = sim, person, goal
        self.goal_pose, self.robot_pose = goal_pose, robot_pose
        self.personality = personality
        self.time_limit = round(_TIME_BASE + _TIME_PER_METRE * route_length, 1)
        self.episode = GuideEpisode(sim.seed, sim.world.name, person, personality.value, goal,
                                    round(route_length, 2), doors, time_limit=self.time_limit)
        self._nearest = math.inf
        self._fastest = 0.0
        self._last = (sim.people[person].position, sim.clock.now())
        self._began = time.perf_counter()
        self._t0 = sim.clock.now()

    def start(self, body: SimBody) -> None:
        """Set how the person follows, and watch the truth every tick."""
        sim = self.sim
        body.hearing.personalities[self.person] = self.personality
        self._t0 = sim.clock.now()
        self._began = time.perf_counter()

        self._last = (sim.people[self.person].position, sim.clock.now())

        def watch() -> None:
            here, now = sim.people[self.person].position, sim.clock.now()
            self._nearest = min(self._nearest, math.dist(sim.robot_pose[:2], here))
            before, then = self._last
            if now > then:
                self._fastest = max(self._fastest, math.dist(here, before) / (now - then))
            self._last = (here, now)

        body.referees.append(watch)

    def judge(self, robot_verdict: str) -> GuideEpisode:
        """The verdict by the truth, once the robot's Guide skill ended (``robot_verdict``:
        its status)."""
        sim, episode = self.sim, self.episode
        episode.robot_verdict = robot_verdict
        episode.end_distance = round(math.dist(sim.people[self.person].position,
                                               self.goal_pose.xy()), 3)
        episode.sim_seconds = round(sim.clock.now() - self._t0, 2)
        episode.in_time = episode.sim_seconds <= self.time_limit
        did = [event.data.get("did") for event in sim.events.of_kind("sim.person")
               if event.data.get("person") == self.person]
        episode.wandered_off = did.count("wandered off")
        episode.fetched = did.count("follows again")
        episode.noticed = sum(1 for _ in sim.events.of_kind("robot.guide_lost"))
        episode.waited = sum(1 for _ in sim.events.of_kind("robot.guide_waiting"))
        episode.collisions = list(sim.collisions)
        episode.person_collisions = sum(1 for hit in sim.collisions
                                        if hit.get("with") == f"person {self.person}")
        episode.nearest = round(self._nearest, 3) if math.isfinite(self._nearest) else 0.0
        episode.fastest = round(self._fastest, 3)
        episode.at_goal = episode.end_distance <= GOAL_REACH
        episode.success = (episode.at_goal and episode.in_time
                           and not episode.collisions)
        episode.wall_seconds = round(time.perf_counter() - self._began, 2)
        return episode


def guide_arena(world: World, seed: int, navigator: Navigator) -> GuideArena | GuideEpisode:
    """The arena of a seeded episode: the person in place and the robot before them (its
    pose ``GuideArena.robot_pose``, which the robot is told); a skipped ``GuideEpisode``
    when the home has no such start and goal."""
    sim = Simulation(world, seed=seed, navigator=navigator)
    rng = np.random.default_rng([seed, 3737])
    spots = _open_floor(navigator, world)
    people = sorted(name for name, person in world.people.items() if person.cooperative)
    shut = frozenset(name for name, state in sim.door_state.items()
                     if state is not DoorState.OPEN)
    goals = sorted(name for name, placement in world.placements.items()
                   if placement.model.kind is PlacementKind.FURNITURE)
    for _ in range(300):
        if not people or not spots or not goals:
            break
        person = people[int(rng.integers(len(people)))]
        start = spots[int(rng.integers(len(spots)))]
        facing = float(rng.uniform(-math.pi, math.pi))
        robot = (start[0] + _IN_FRONT * math.cos(facing), start[1] + _IN_FRONT * math.sin(facing))
        if not free_floor(navigator, robot, world.robot.radius + 0.15) or \
                world.room_at(*robot) != world.room_at(*start):
            continue
        if any(math.dist(state.position, spot) < _ROOM_AROUND for name, state in
               sim.people.items() if name != person for spot in (start, robot)):
            continue
        goal = goals[int(rng.integers(len(goals)))]
        approach = world.placements[goal].approach
        if world.room_at(*approach.xy()) == world.room_at(*start):
            continue
        plan = navigator.plan(robot, approach.xy(), shut)
        if plan is None or not plan.doors or \
                not ROUTE_LENGTH[0] <= plan.length <= ROUTE_LENGTH[1]:
            continue
        return arranged_arena(sim, person, start, robot, goal, personality_of(seed, person))
    return GuideEpisode(seed, world.name, skipped="no free start and goal 6-20 m away")


def arranged_arena(sim: Simulation, person: str, start: tuple[float, float],
                   robot: tuple[float, float], goal: str, personality: Personality
                   ) -> GuideArena:
    """An arena in ``sim`` as given: ``person`` (following as ``personality`` says) stands
    at ``start``, the robot at ``robot`` facing them, and is to guide them to the furniture
    ``goal``."""
    sim.move_person(person, start)
    sim.people[person].got_up = True  # whoever sat, stands up to be guided
    heading = math.atan2(start[1] - robot[1], start[0] - robot[0])
    robot_pose = Pose(robot[0], robot[1], heading)
    sim.robot_pose = (robot_pose.x, robot_pose.y, robot_pose.theta)
    approach = sim.world.placements[goal].approach
    plan = sim.navigator.plan(robot, approach.xy())
    length, doors = (plan.length, len(plan.doors)) if plan is not None else (0.0, 0)
    return GuideArena(sim, person, personality, goal, approach, robot_pose, length, doors)


def _open_floor(navigator: Navigator, world: World) -> list[tuple[float, float]]:
    """Spots every 30 cm with ``_CLEAR`` metres of floor round them, in some room, off the
    doorways."""
    clearance = navigator.clearance()
    x0, y0, x1, y1 = world.bounds()
    spots = []
    for x in np.arange(x0 + 0.15, x1, 0.3):
        for y in np.arange(y0 + 0.15, y1, 0.3):
            spot = (round(float(x), 2), round(float(y), 2))
            if clearance[navigator.grid.cell_of(*spot)] >= _CLEAR and \
                    world.room_at(*spot) is not None and \
                    all(math.dist(spot, door.position) > 1.0 for door in world.doors.values()):
                spots.append(spot)
    return spots

