"""Follow Me (RoboCup@Home; Cosero §8.2): the operator walks through the home, the robot
follows, and stops when told to.

One episode, in the embodied fidelity, seeded:

- the operator (one of the home's people) stands in free floor with the robot 1.3 m
  behind them, facing them; the robot is told where it starts, nothing else;
- the operator walks a route of their own through 15–25 m of the home (two to four
  places in other rooms, through doors, which they open when shut), at a slow walking
  pace, pausing at some corners (``homebot.sim.routes``);
- two other people cross the route between the operator and the robot, on their own,
  setting off as the operator comes by;
- at the end the operator turns to the robot and says "stop" (one of a few phrasings),
  aloud, or, one time in three, shows the stop gesture (a raised open hand held out).

The robot (built by the caller, ``homebot.bench.follow``) follows from the start.
The referee watches the simulator's truth every tick (``SimBody.referees``) and never the
robot's report: the episode succeeds when the robot stayed within ``WITHIN`` metres of the
operator throughout, ended following within ``STOP_WITHIN`` seconds of the operator's
"stop", stood still afterwards, and touched nobody and nothing.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.navigator import point_along, polyline_length
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.body_tracker import person_height
from homebot.sim.keypoints import draw_motion
from homebot.sim.routes import RouteWalk, plan_route
from homebot.trials.arena import free_floor
from homebot.world import World

__all__ = ["STOPPED_BY", "STOP_WITHIN", "WITHIN", "FollowEpisode", "FollowMeArena",
           "follow_me_arena"]

WITHIN = 3.0  #: metres: the robot keeps this close to the operator
#: the robot's reason for ending that counts as stopping when told, by how it was told
STOPPED_BY = {"voice": "stop_said", "gesture": "stop_shown"}
_SHOWN_STOP = 1.0 / 3.0  #: the share of operators who show the stop gesture instead of saying it
STOP_WITHIN = 5.0  #: seconds after "stop" is said within which following ends
ROUTE_LENGTH = (15.0, 25.0)  #: metres the operator walks
#: m/s: the operator's pace, a slow walk that a robot with the shipped worlds' top speed
#: (0.5 m/s) can keep up with, as RoboCup@Home operators walk for their robots
_PACE = (0.3, 0.45)
_CROSSING_PACE = (0.5, 0.8)  #: m/s: the passers-by's
_BEHIND = 1.3  #: metres from the operator to the robot at the start
_CLEAR = 0.5  #: metres of free floor round every spot a person is sent to
_CROSSING_REACHES = (1.8, 1.4, 1.1)  #: metres a passer-by starts and ends either side
_CROSSING_SHARES = ((0.35, 0.3, 0.45), (0.65, 0.55, 0.75))  #: where along the route they cross
_ROOM_AROUND = 1.5  #: metres round the start where nobody else stands
_SETS_OFF_NEAR = 1.2  #: metres from the crossing at which the operator sets a passer-by off
_SET_OFF = 2.0  #: seconds after the start at which the operator sets off
_STILL_AFTER = 3.0  #: seconds after following ended during which the robot must stand still
_STOP_PHRASES = ("Stop.", "Stop here.", "You can stop now.", "Okay robot, stop.",
                 "Stop following me.")


@dataclass
class FollowEpisode:
    """One Follow Me run and the referee's verdict (truth only)."""

    seed: int
    world: str
    operator: str = ""
    route_length: float = 0.0
    crossers: int = 0
    success: bool = False
    max_gap: float = 0.0  #: metres, the farthest the robot fell behind the operator
    kept_within: bool = False
    stopped: bool = False  #: ended following soon after "stop" and then stood still
    stop_by: str = ""  #: how the operator told the robot to stop: voice or gesture
    stop_delay: float | None = None  #: seconds from "stop" (its end, said) to following's end
    end: str = ""  #: why the robot says following ended
    lost: int = 0  #: times the robot lost the operator and found them again
    collisions: list[dict[str, object]] = field(default_factory=list)
    sim_seconds: float = 0.0
    wall_seconds: float = 0.0
    skipped: str | None = None  #: why no episode could be set up (no route of the length)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


class FollowMeArena:
    """One Follow Me episode's arena and referee (see the module docstring): set up with
    ``follow_me_arena``; ``start`` sets the people going in the robot's body; ``judge``
    gives the verdict once the robot says following ended."""

    def __init__(self, sim: Simulation, navigator: Navigator, seed: int, operator: str,
                 start: tuple[float, float], robot_pose: Pose,
                 route: list[tuple[float, float]], rng: np.random.Generator) -> None:
        self.sim, self.navigator, self.seed, self.operator = sim, navigator, seed, operator
        self.robot_pose, self.route = robot_pose, route
        self.operator_start = start
        self.pace = float(rng.uniform(*_PACE))
        self.episode = FollowEpisode(seed, sim.world.name, operator,
                                     round(polyline_length([start, *route]), 2))
        self._rng = rng
        self._said_end: float | None = None
        self._gaps: list[float] = []
        self._began = time.perf_counter()
        self._t0 = sim.clock.now()

    @property
    def walk_seconds(self) -> float:
        """How long the operator's walk takes without pauses."""
        return self.episode.route_length / self.pace

    def start(self, body: SimBody) -> None:
        """Set the operator and the passers-by walking, and watch."""
        sim, operator, rng = self.sim, self.operator, self._rng
        self._t0 = sim.clock.now()

        self.episode.stop_by = "gesture" if rng.random() < _SHOWN_STOP else "voice"

        def tell_to_stop() -> None:
            if self.episode.stop_by == "gesture":
                body.arms.gestures[operator] = draw_motion(
                    "stop", rng, height=person_height(operator, sim.people[operator].model))
                self._said_end = sim.clock.now()
                return
            phrase = _STOP_PHRASES[int(rng.integers(len(_STOP_PHRASES)))]
            before = len(body.audio.sounds)
            body.hearing.say(operator, phrase)
            sounds = body.audio.sounds[before:]
            self._said_end = sounds[-1].end if sounds else sim.clock.now()

        body.people.walk_route(RouteWalk(operator, list(self.route), self.pace,
                                         starts_at=self._t0 + _SET_OFF, at_end=tell_to_stop,
                                         seed=self.seed))
        self.episode.crossers = _send_crossers(sim, body, self.navigator, operator,
                                               self.operator_start, self.route, rng)

        def watch() -> None:
            if self._said_end is None and sim.clock.now() >= self._t0 + _SET_OFF:
                self._gaps.append(math.dist(sim.robot_pose[:2],
                                            sim.people[operator].position))

        body.referees.append(watch)

    def judge(self, body: SimBody, end: str, lost: int) -> FollowEpisode:
        """The verdict, by the truth, once the robot says following ended (``end``: why,
        ``lost``: times it lost the operator): it must then stand still."""
        sim, episode = self.sim, self.episode
        ended = sim.clock.now()
        resting = sim.robot_pose[:2]
        body.tick(round(_STILL_AFTER / body.tick_period))
        still = math.dist(resting, sim.robot_pose[:2]) < 0.1
        episode.end, episode.lost = end, lost
        episode.max_gap = round(max(self._gaps, default=0.0), 3)
        episode.kept_within = bool(self._gaps) and episode.max_gap <= WITHIN
        if self._said_end is not None:
            episode.stop_delay = round(ended - self._said_end, 3)
        episode.stopped = (end == STOPPED_BY[episode.stop_by] and episode.stop_delay is not None
                           and -0.5 <= episode.stop_delay <= STOP_WITHIN and still)
        episode.collisions = list(sim.collisions)
        episode.success = episode.kept_within and episode.stopped and not episode.collisions
        episode.sim_seconds = round(sim.clock.now() - self._t0, 2)
        episode.wall_seconds = round(time.perf_counter() - self._began, 2)
        return episode


def follow_me_arena(world: World, seed: int, navigator: Navigator
                    ) -> FollowMeArena | FollowEpisode:
    """The arena of a seeded episode: the operator in place and the robot behind them
    (its pose ``FollowMeArena.robot_pose``, which the robot is told); a skipped
    ``FollowEpisode`` when the home has no route of the length."""
    sim = Simulation(world, seed=seed, navigator=navigator)
    rng = np.random.default_rng([seed, 4242])
    arena = _arena(sim, navigator, rng)
    if arena is None:
        return FollowEpisode(seed, world.name, skipped="no free start and route of 15-25 m")
    operator, start, robot_pose, route = arena
    sim.move_person(operator, start)
    sim.people[operator].got_up = True  # whoever sat or lay in the world file, stands
    sim.robot_pose = (robot_pose.x, robot_pose.y, robot_pose.theta)
    return FollowMeArena(sim, navigator, seed, operator, start, robot_pose, route, rng)


# ------------------------------------------------------------ the arena


def _arena(sim: Simulation, navigator: Navigator, rng: np.random.Generator
           ) -> tuple[str, tuple[float, float], Pose, list[tuple[float, float]]] | None:
    """The operator, where they start, the robot's pose behind them, and their route."""
    world = sim.world
    spots = _open_floor(navigator, world)
    people = sorted(sim.people)
    for _ in range(200):
        operator = people[int(rng.integers(len(people)))]
        start = spots[int(rng.integers(len(spots)))]
        route = _route(sim, spots, start, rng)
        if route is None:
            continue
        heading = math.atan2(route[0][1] - start[1], route[0][0] - start[0])
        behind = (start[0] - _BEHIND * math.cos(heading), start[1] - _BEHIND * math.sin(heading))
        if not free_floor(navigator, behind, world.robot.radius + 0.15) or \
                world.room_at(*behind) != world.room_at(*start):
            continue
        if any(math.dist(state.position, spot) < _ROOM_AROUND for name, state in
               sim.people.items() if name != operator for spot in (start, behind)):
            continue  # nobody else stands right at the start
        return operator, start, Pose(behind[0], behind[1], heading), route
    return None


def _route(sim: Simulation, spots: list[tuple[float, float]], start: tuple[float, float],
           rng: np.random.Generator) -> list[tuple[float, float]] | None:
    """Two to four places in turn, each in another room, 15-25 m of walking in all."""
    world = sim.world
    places: list[tuple[float, float]] = []
    here = start
    for _ in range(4):
        others = [spot for spot in spots if world.room_at(*spot) != world.room_at(*here)]
        if not others:
            return None
        here = others[int(rng.integers(len(others)))]
        places.append(here)
        route = plan_route(sim, start, places)
        if route is None:
            return None
        length = polyline_length([start, *route])
        if length > ROUTE_LENGTH[1]:
            return None
        if length >= ROUTE_LENGTH[0] and len(places) >= 2:
            return route
    return None


def _send_crossers(sim: Simulation, body: SimBody, navigator: Navigator, operator: str,
                   start: tuple[float, float], route: list[tuple[float, float]],
                   rng: np.random.Generator) -> int:
    """Two other people cross the route a third and two thirds of the way along, just
    after the operator passed (between the operator and the robot); how many could."""
    others = [name for name in sorted(sim.people) if name != operator]
    rng.shuffle(others)
    points = [start, *route]
    total = polyline_length(points)
    sent = 0
    for shares in _CROSSING_SHARES:
        if sent >= len(others):
            break
        crossing = _crossing(navigator, points, total, shares, rng,
                             away_from=(start, sim.robot_pose[:2]))
        if crossing is None:
            continue
        ends = crossing
        name = others[sent]
        crossing_pace = float(rng.uniform(*_CROSSING_PACE))
        sim.move_person(name, ends[0])
        sim.people[name].got_up = True
        middle = ((ends[0][0] + ends[1][0]) / 2, (ends[0][1] + ends[1][1]) / 2)

        def operator_near(middle: tuple[float, float] = middle) -> bool:
            # they set off as the operator comes by: they cross just behind them
            return math.dist(sim.people[operator].position, middle) <= _SETS_OFF_NEAR

        body.people.walk_route(RouteWalk(
            name, [ends[1]], crossing_pace, pause_chance=0.0, starts_when=operator_near,
            seed=sim.seed + 17 * sent))
        sent += 1
    return sent


def _crossing(navigator: Navigator, points: list[tuple[float, float]], total: float,
              shares: tuple[float, ...], rng: np.random.Generator,
              away_from: tuple[tuple[float, float], ...]
              ) -> list[tuple[float, float]] | None:
    """Where a passer-by crossing the route (at one of ``shares`` of its length) starts and ends,
    on free floor either side, not at the start (``away_from``: the operator's and the
    robot's spots); None: nowhere near those shares."""
    side = 1 if rng.random() < 0.5 else -1
    for share in shares:
        found = point_along(points, share * total)
        if found is None:
            continue
        (x, y), heading = found
        normal = (-math.sin(heading), math.cos(heading))
        for reach in _CROSSING_REACHES:
            ends = [(x + side * sign * reach * normal[0], y + side * sign * reach * normal[1])
                    for sign in (1, -1)]
            if all(free_floor(navigator, end, 0.3) and
                   min(math.dist(end, spot) for spot in away_from) >= _ROOM_AROUND
                   for end in ends):
                return ends
    return None


def _open_floor(navigator: Navigator, world: World) -> list[tuple[float, float]]:
    """Spots every 30 cm with ``_CLEAR`` metres of floor round them, in some room."""
    grid = navigator.grid
    clearance = navigator.clearance()
    x0, y0, x1, y1 = world.bounds()
    spots = []
    for x in np.arange(x0 + 0.15, x1, 0.3):
        for y in np.arange(y0 + 0.15, y1, 0.3):
            cell = grid.cell_of(float(x), float(y))
            if clearance[cell] >= _CLEAR and world.room_at(float(x), float(y)) is not None \
                    and all(math.dist((x, y), door.position) > 1.0
                            for door in world.doors.values()):
                spots.append((round(float(x), 2), round(float(y), 2)))
    return spots

