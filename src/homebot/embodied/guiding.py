"""Guiding a person by tracking them (Cosero §8.2): the robot leads, and looks back.

The robot drives its route to the goal in stretches (``BodyRobot.move_with``: ``move_to``
with the person as a companion who may show stop, so doors are looked at and passed as
ever): ``GuideParameters.look_every``
metres at most, and a stretch ends before every door. After each stretch it looks back
for the person it guides, with its leg tracker (``perception.people``: legs in the laser,
tracked over a second of sweeps); of several people there, the one nearest where the
follower should be, dressed as they were at the start, and never one whose face the head
camera knows as someone else's.

Why stop and turn to look: the laser sees 270° in front, so someone walking a metre
straight behind the robot stands in its blind cone, and the head camera's turn
(±2.6 rad) does not reach straight back either. Driving with the person kept at an
angle would need a wide way, which corridors and doorways are not. So the robot stops
and turns its base just far enough that where the person should be (on its own trail,
about a metre back) lies ``GuideParameters.side_on`` radians off its heading: well inside
the laser's view and the head's turn (the camera then checks their clothes and face), and
a quarter turn rather than a half one; not seen there, it turns to face that spot. Before
a door it looks so as not to leave anyone behind in another room.

- Seen near (within ``keeps_up``; at the goal, ``at_goal``): on to the next stretch.
- Seen farther back (a slow walker, someone who stopped to look round): the robot
  waits (``robot.guide_waiting``), watching them come; someone seen who stands still
  for ``stalled`` seconds instead of coming is fetched.
- Not seen: the robot watches for ``lost_after`` seconds (they may be round a corner);
  then it says it lost them (``robot.guide_lost``) and searches: back where it last saw
  them, looking all round, then just through each door near there (someone who stepped
  into the next room is out of the laser's sight through a doorway), then the same
  round where they should have been, just behind it. It drives up to each person its
  tracker finds there, recognises them by face (someone else is passed over), and asks
  again "please follow me" by name: a yes heard is them (``robot.guide_fetched``),
  silence someone else. Then it leads on from there.

At the goal it turns to face them, so that a look (the Guide skill's monitor) sees and
names them. Nothing here reads the simulator: the person is only what the laser, the
head camera and the face close-ups show.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from shapely.geometry import LineString
from shapely.geometry import Point as ShapelyPoint

from homebot.cancel import CancelToken
from homebot.embodied.people_look import UNREAD
from homebot.geometry import Pose, wrap_angle
from homebot.perception.people import PeopleTracker, Track, detect_legs
from homebot.robot import Blocker, MoveReport, Twist

if TYPE_CHECKING:
    from homebot.embodied.robot import BodyRobot

__all__ = ["GuideParameters", "Guiding"]

_PAN_LIMIT = 2.6  #: radians the head turns either way
_FACE_RANGE = 2.5  #: metres within which the head camera's close-up shows a face


@dataclass(frozen=True, slots=True)
class GuideParameters:
    """How often the robot looks back, how long it waits, how it searches."""

    look_every: float = 4.0  #: metres driven between looks back
    door_slack: float = 1.0  #: metres: a door this much farther is looked back before
    side_on: float = 1.3  #: radians off its heading where the robot turns the person to
    watch: float = 1.0  #: seconds of laser sweeps per look
    behind: float = 1.0  #: metres back along its trail where the person should walk
    keeps_up: float = 2.2  #: metres: someone this near the robot keeps up
    at_goal: float = 1.4  #: metres: at the goal, the robot waits until they are this near
    reach: float = 5.0  #: metres round the robot within which the person is looked for
    wait: float = 40.0  #: seconds the robot waits for someone coming
    stalled: float = 6.0  #: seconds someone seen behind stands still before being fetched
    lost_after: float = 6.0  #: seconds unseen before the robot says it lost them
    fetch_distance: float = 1.1  #: metres from the person where the robot asks again
    search_reach: float = 5.0  #: metres round where they were last seen that it searches
    door_reach: float = 3.5  #: metres from there to a door it looks through
    through_door: float = 1.0  #: metres into the next room where it stands to look round
    fetches: int = 3  #: times it goes back for them at most


@dataclass
class _Follower:
    """What the robot knows of the person it guides."""

    position: tuple[float, float] | None = None  #: where last seen
    seen_from: tuple[float, float] | None = None  #: where the robot stood then
    wears: str | None = None  #: the colour of their top, as the camera saw it


class Guiding:
    """Leads one person to a goal with a ``BodyRobot`` (see the module docstring)."""

    def __init__(self, robot: BodyRobot, parameters: GuideParameters | None = None) -> None:
        self.robot = robot
        self.parameters = parameters or GuideParameters()
        self.tracker = PeopleTracker()
        self._follower = _Follower()
        self._came_from: tuple[float, float] | None = None
        self._person: str | None = None

    def guide(self, person: str, goal: Pose, avoid_doors: frozenset[str] = frozenset(), *,
              cancel: CancelToken | None = None) -> MoveReport:
        """Lead ``person`` (just asked to follow) to ``goal``; the motion's report."""
        robot, p = self.robot, self.parameters
        events = robot.events
        self._person = person
        self._first_sight()
        events.record("robot.guiding", person=person, seen=self._follower.position is not None)
        travelled, fetches = 0.0, 0
        passed: list[str] = []
        stood_before: str | None = None
        while True:
            if cancel is not None and cancel.cancelled:
                return MoveReport(False, robot.pose(), travelled, Blocker.CANCELLED,
                                  doors_passed=tuple(passed))
            stretch = self._next_stretch(goal, avoid_doors, stood_before)
            if stretch is None:
                return MoveReport(False, robot.pose(), travelled, Blocker.NO_PATH,
                                  doors_passed=tuple(passed))
            target, stood_before, final = stretch
            self._came_from = robot.pose().xy()
            report = robot.move_with(person, target, avoid_doors, cancel=cancel)
            travelled += report.distance
            passed.extend(report.doors_passed)
            if not report.reached:
                return replace(report, distance=travelled, doors_passed=tuple(passed))
            with_us, went_back = self._check(p.at_goal if final else p.keeps_up), False
            while not with_us and fetches < p.fetches:
                fetches, went_back = fetches + 1, True
                with_us = self._fetch(person, cancel)
            if went_back:
                stood_before = None  # lead on from where they were found
            if final and (not went_back or math.dist(robot.pose().xy(), goal.xy()) <= 0.3):
                self._face_follower()
                return MoveReport(True, robot.pose(), travelled, doors_passed=tuple(passed))

    # ------------------------------------------------------------ the route

    def _next_stretch(self, goal: Pose, avoid_doors: frozenset[str], stood_before: str | None
                      ) -> tuple[Pose, str | None, bool] | None:
        """The next place to stop and look back: (pose, the door it stands before there,
        whether it is the goal); None: no way to the goal."""
        robot, p = self.robot, self.parameters
        here = robot.pose().xy()
        plan = robot.navigator.plan(here, goal.xy(), avoid_doors)
        if plan is None:
            return None
        if len(plan.waypoints) < 2 or plan.length <= p.look_every * 1.3:
            return (goal, None, True)
        way = LineString(plan.waypoints)
        stop_at = p.look_every
        for index, door in enumerate(plan.doors):
            if door == stood_before:
                continue  # through it now
            along = way.project(ShapelyPoint(robot.world.doors[door].position))
            if along <= p.look_every + p.door_slack:
                return (robot.world.point_before_door(door, plan.route.rooms[index], 0.6),
                        door, False)
            break
        if stop_at >= way.length - 0.5:
            return (goal, None, True)
        point = way.interpolate(stop_at)
        ahead = way.interpolate(min(way.length, stop_at + 0.3))
        return (Pose(point.x, point.y, math.atan2(ahead.y - point.y, ahead.x - point.x)),
                None, False)

    # ------------------------------------------------------------ looking

    def _first_sight(self) -> None:
        """The person was just asked, in front of the robot: the nearest person within
        reach, and what they wear."""
        robot = self.robot
        pose = self._watch()
        near = [track for track in self.tracker.confirmed()
                if math.dist(track.position, pose.xy()) <= 2.5]
        if not near:
            return
        chosen = min(near, key=lambda track: math.dist(track.position, pose.xy()))
        self._saw(chosen.position, pose)
        look = robot.people_look
        wears = look.clothes_at(robot.localise(), chosen.position) if look else None
        self._follower.wears = wears[0] if wears and wears != UNREAD else None

    def _check(self, near: float) -> bool:
        """Look back for the follower; wait while they come; whether they are with the
        robot (else lost, or standing apart: to be fetched)."""
        p, robot = self.parameters, self.robot
        seen = self._look_back()
        waited_since = robot.now()
        if seen is None:  # off where expected: look straight at where they should be
            pose = robot.localise()
            robot.navigation.face(self._expected(pose))
            seen = self._find_in(self._watch())
        if seen is None:
            while seen is None and robot.now() - waited_since < p.lost_after:
                seen = self._find_in(self._watch())
            if seen is None:
                return False
        pose = robot.pose()
        if math.dist(seen, pose.xy()) <= near:
            return True
        robot.events.record("robot.guide_waiting", person=self._person,
                            at=[round(v, 2) for v in seen])
        closest, closest_since = math.dist(seen, pose.xy()), robot.now()
        while robot.now() - waited_since < p.wait:
            found = self._find_in(self._watch())
            if found is None:
                continue
            gap = math.dist(found, robot.pose().xy())
            if gap <= near:
                return True
            if gap < closest - 0.3:
                closest, closest_since = gap, robot.now()
            elif robot.now() - closest_since >= p.stalled:
                return False  # standing apart: fetch them
        return False

    def _look_back(self) -> tuple[float, float] | None:
        """Turn so that where the follower should be lies ``side_on`` off the heading, and
        watch: where they are, or None."""
        robot = self.robot
        pose = robot.localise()
        expected = self._expected(pose)
        bearing = math.atan2(expected[1] - pose.y, expected[0] - pose.x)
        off = wrap_angle(bearing - pose.theta)
        if abs(off) > self.parameters.side_on:
            heading = bearing - math.copysign(self.parameters.side_on, off)
            robot.navigation.face((pose.x + math.cos(heading), pose.y + math.sin(heading)))
        return self._find_in(self._watch())

    def _expected(self, pose: Pose) -> tuple[float, float]:
        """Where the follower should be: ``behind`` metres back the way the robot came."""
        came_from = self._came_from
        if came_from is None or math.dist(came_from, pose.xy()) < 0.2:
            return self._follower.position or (pose.x - math.cos(pose.theta),
                                               pose.y - math.sin(pose.theta))
        away = math.dist(came_from, pose.xy())
        back = min(self.parameters.behind, away)
        return (pose.x + (came_from[0] - pose.x) * back / away,
                pose.y + (came_from[1] - pose.y) * back / away)

    def _watch(self) -> Pose:
        """Stand and feed the tracker ``watch`` seconds of sweeps; the pose."""
        robot = self.robot
        body = robot.body
        body.command_velocity(Twist())
        pose = robot.localise()
        for _ in range(max(1, round(self.parameters.watch / body.tick_period))):
            body.tick()
            pose = robot.localise()
            self._update(pose)
        return pose

    def _update(self, pose: Pose) -> list[Track]:
        body = self.robot.body
        scan = body.scan()
        legs = detect_legs(scan, pose)
        look = self.robot.people_look
        if len(legs) and look is not None:
            legs = legs[look.off_the_map(legs)]
        return self.tracker.update(body.now(), legs, scan, pose)

    def _find_in(self, pose: Pose) -> tuple[float, float] | None:
        """The follower among the tracks seen now: the nearest to where they should be,
        within ``reach``; of several, one dressed as they are first (clothes told wrong
        never hide the only one there); never one whose face is someone else's."""
        now = self.robot.body.now()
        expected = self._expected(pose)
        candidates = sorted((track for track in self.tracker.confirmed()
                             if track.seen >= now - 1e-9 and
                             math.dist(track.position, pose.xy()) <= self.parameters.reach),
                            key=lambda track: math.dist(track.position, expected))
        if len(candidates) > 1:
            candidates.sort(key=lambda track: self._dressed_otherwise(pose, track.position))
        for track in candidates:
            if self._someone_else(pose, track.position):
                continue
            self._saw(track.position, pose)
            return track.position
        return None

    def _someone_else(self, pose: Pose, where: tuple[float, float]) -> bool:
        """Whether the face of whoever stands at ``where`` is known as someone else's
        (False when the head cannot turn to them, they are beyond face range, or the face
        is not recognised)."""
        robot, person = self.robot, self._person
        bearing = wrap_angle(math.atan2(where[1] - pose.y, where[0] - pose.x) - pose.theta)
        if person is None or abs(bearing) > _PAN_LIMIT or \
                math.dist(where, pose.xy()) > _FACE_RANGE:
            return False
        robot.body.point_head(bearing, 0.0)
        name = robot.face_in_front()
        robot.body.point_head(0.0, 0.0)
        return name is not None and name != person

    def _dressed_otherwise(self, pose: Pose, where: tuple[float, float]) -> bool:
        look, wears = self.robot.people_look, self._follower.wears
        if look is None or wears is None:
            return False
        seen = look.clothes_at(pose, where)
        return bool(seen) and seen != UNREAD and seen is not None and seen[0] != wears

    def _saw(self, where: tuple[float, float], pose: Pose) -> None:
        self._follower.position, self._follower.seen_from = where, pose.xy()

    # ------------------------------------------------------------ fetching

    def _fetch(self, person: str, cancel: CancelToken | None) -> bool:
        """Look for the follower round where they were last seen, then round where they
        should have been (just behind); find them (tracker and face), and ask them again to
        follow; whether they were found and asked."""
        robot = self.robot
        last = self._follower.position
        robot.say(f"I have lost {person}. I will go back and look for them.")
        robot.events.record("robot.guide_lost", person=person,
                            last_seen=None if last is None else [round(v, 2) for v in last])
        behind = self._expected(robot.localise())
        centres = [behind] if last is None else [last] if math.dist(last, behind) < 2.0 \
            else [last, behind]
        spots: list[tuple[Pose, tuple[float, ...]]] = []
        for centre in centres:
            spots.extend(spot for spot in self._search_spots(centre)
                         if all(math.dist(spot[0].xy(), other[0].xy()) > 1.0 for other in spots))
        tried: list[tuple[float, float]] = []
        for spot, turns in spots:
            if cancel is not None and cancel.cancelled:
                return False
            if self._search_at(person, spot, turns, centres, tried, cancel):
                return True
        return False

    def _search_at(self, person: str, spot: Pose, turns: tuple[float, ...],
                   centres: list[tuple[float, float]], tried: list[tuple[float, float]],
                   cancel: CancelToken | None) -> bool:
        """Look round from ``spot`` for the follower, among the people within
        ``search_reach`` of the ``centres`` and not ``tried`` already; whether they were
        found and asked."""
        robot, p = self.robot, self.parameters
        if math.dist(robot.pose().xy(), spot.xy()) > 0.5:
            robot.move_to(spot, cancel=cancel)
        robot.navigation.face((spot.x + math.cos(spot.theta), spot.y + math.sin(spot.theta)))
        pose = robot.localise()
        for turn in turns:
            if turn:
                heading = pose.theta + turn
                robot.navigation.face((pose.x + math.cos(heading),
                                       pose.y + math.sin(heading)))
            pose = self._watch()
            candidates = sorted(
                (track.position for track in self.tracker.confirmed()
                 if track.seen >= robot.body.now() - 1e-9
                 and min(math.dist(track.position, centre) for centre in centres)
                 <= p.search_reach
                 and all(math.dist(track.position, other) > 0.5 for other in tried)),
                key=lambda where: math.dist(where, robot.pose().xy()))
            robot.events.record("robot.guide_search", at=[round(v, 2) for v in pose.xy()],
                                seen=[[round(v, 2) for v in where] for where in candidates])
            for where in candidates:
                tried.append(where)
                if self._ask_if_them(person, where, cancel):
                    return True
                pose = robot.localise()
        return False

    def _search_spots(self, last: tuple[float, float]
                      ) -> list[tuple[Pose, tuple[float, ...]]]:
        """Where to look for someone last seen at ``last``, and the turns to make there:
        near that spot, all round; then just through each door of its room within
        ``door_reach`` of it, all round, nearest the robot first (they may have stepped
        into the next room, where the laser sees little through the doorway)."""
        robot, p = self.robot, self.parameters
        all_round = (0.0, 2.4)  # the laser's 270 degrees, then the cone behind
        spots: list[tuple[Pose, tuple[float, ...]]] = []
        near = self._spot_before(last)
        if near is not None:
            spots.append((near, all_round))
        room = robot.world.room_at(*last)
        if room is None:
            return spots
        here = robot.pose().xy()
        doors = sorted((math.dist(door.position, here), name)
                       for name, door in robot.world.doors.items()
                       if room in door.rooms and math.dist(door.position, last) <= p.door_reach)
        for _, name in doors:
            beyond = next(other for other in robot.world.doors[name].rooms if other != room)
            inside = robot.world.point_before_door(name, beyond, p.through_door)
            spots.append((Pose(inside.x, inside.y, inside.theta + math.pi), all_round))
        return spots

    def _ask_if_them(self, person: str, where: tuple[float, float],
                     cancel: CancelToken | None) -> bool:
        """Come up to whoever stands at ``where``; if their face is not someone else's,
        ask them to follow again."""
        robot = self.robot
        if math.dist(robot.pose().xy(), where) > self.parameters.fetch_distance + 0.3:
            spot = self._spot_before(where)
            if spot is None:
                return False
            robot.move_to(spot, cancel=cancel)
        robot.navigation.face(where)
        robot.body.point_head(0.0, 0.0)
        robot.body.tick()
        name = robot.face_in_front()
        if name is not None and name != person:
            return False
        robot.say(f"{person}, please follow me.")
        if not robot.conversation.agreed():
            return False  # someone else, who does not answer to the name
        robot.events.record("robot.guide_fetched", person=person,
                            at=[round(v, 2) for v in where], face=name)
        self._saw(where, robot.pose())
        self._came_from = None
        return True

    def _spot_before(self, where: tuple[float, float]) -> Pose | None:
        """Where to stand to speak to someone at ``where``: ``fetch_distance`` short of them
        on the way there, facing them."""
        robot = self.robot
        plan = robot.navigator.plan(robot.pose().xy(), where)
        if plan is None or len(plan.waypoints) < 2:
            return None
        way = LineString(plan.waypoints)
        spot = way.interpolate(max(way.length - self.parameters.fetch_distance, 0.0))
        return Pose(spot.x, spot.y, math.atan2(where[1] - spot.y, where[0] - spot.x))

    def _face_follower(self) -> None:
        """At the goal: turn to the follower, so that a look sees them."""
        where = self._follower.position
        if where is not None:
            self.robot.navigation.face(where)
