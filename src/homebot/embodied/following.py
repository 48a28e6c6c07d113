"""Following a person by tracking them with the laser (Cosero §7.1.1, §8.2 *Follow Me*).

The robot keeps the person it follows as one track of its leg tracker
(``perception.people.PeopleTracker``: a Kalman filter per person over the laser's leg
detections). It drives along the way the person walked (their trail: free floor, and
through doorways where people go), steering by pure pursuit a short way ahead and stopping
``FollowParameters.distance`` short of them; each doorway on the way is crossed square (a
point in front of it, its middle, a point beyond), a robot standing in a doorway's frame
leaves it straight before turning, and where the person was hidden and found again past a
door frame, the trail's gap is bridged by the map's way round. Where something stands in
the strip the base would drive through, the robot turns towards its way on when that is
free, else the local controller steers round it; where the person's way is
too tight for the robot (someone seated beside it), the robot plans round what the laser
sees that the map lacks.

Someone crossing between the robot and the person, a corner or a door frame hides the
person. The tracker coasts the track for a while; when it ends, the robot re-identifies
the person among the tracks that start near where the person was heading. A track that was
seen at the same time as the person, somewhere else, is someone else, and is taken for
them again only when the camera sees their clothes; so is a track once dropped for other
clothes, and someone standing still far from where the walking person was heading. The
head camera keeps the person in view: what they wear (the colour of their top, as
``PeopleLook.clothes_at`` reads it) is learnt at the start and checked every
``FollowParameters.check_every`` seconds, so a track that slipped onto someone else (two
people passing close, the tracker's legs swapped) is dropped for a while, and a candidate
in other clothes is not taken. The camera is not asked while someone nearer stands in its
line of sight, or someone stands right beside the person. Faces are no help here: the
person walks ahead, their back to the robot. Not found again, the robot keeps to where the
person was heading; after ``FollowParameters.give_up`` seconds it reports the person lost.
Stalled by someone standing on its way, the robot asks them, once, to let it through.

Following ends when the person says "stop" (the microphone, heard in the ``stop``
state), shows the stop gesture (when the robot can read gestures), stands still in the
room they were to lead it to, or, without such a room, stands still for
``FollowParameters.still_end`` seconds. Nothing here reads the simulator: the person is
only what the laser shows.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

from homebot.cancel import CancelToken
from homebot.embodied.people_look import UNREAD
from homebot.errors import PartMissing
from homebot.events import EventLog
from homebot.geometry import Pose, wrap_angle
from homebot.navigation import Navigator
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigator import point_along, polyline_length
from homebot.perception.body_parts import looking_tilt
from homebot.perception.people import PeopleTracker, Track, detect_legs
from homebot.robot import Body, CameraIntrinsics, LaserScan, RgbdFrame, Twist
from homebot.world import World

__all__ = ["FollowEnd", "FollowParameters", "FollowResult", "Following", "shortened"]

_OWN_LEGS = 0.6  #: metres round the person followed whose returns are their own legs
#: metres from the person beyond which a track seen with them is someone else for good (a
#: nearer one may be them, the tracker having swapped two people passing close)
_SURELY_SOMEONE_ELSE = 1.5
#: metres from the camera's line of sight to the person within which someone nearer hides them
_IN_THE_WAY = 0.4
#: metres between two people within which the camera cannot tell which is which
_SIDE_BY_SIDE = 0.9
#: seconds a track dropped for showing other clothes is not taken for the person again;
#: after, only when the camera sees their clothes on it (it may be them after all: seen
#: past someone's shoulder, or in another light)
_DROPPED_FOR = 4.0
#: metres from where a walking person lost was heading within which a candidate standing
#: still may be them (they stopped, at a corner or a door); farther, only the camera tells
_STOPPED_NEAR = 1.5
_TRAIL_STEP = 0.15  #: metres between the points kept of the way the person walked
#: metres between two points of the trail beyond which the robot may not fit along the
#: straight line between them (the person was hidden in between)
_TRAIL_GAP = 0.5
_ON_THE_TRAIL = 1.0  #: metres from their trail within which the robot drives along it
_DOORWAY_REACH = 0.6  #: metres either side of a doorway where the robot's way is squared
#: metres either side of a doorway's middle, across its wall, within which the robot
#: stands in its frame
_IN_THE_FRAME = 0.3
#: metres off a doorway's axis within which the robot in front of it drives straight through
_ON_THE_AXIS = 0.1
_STILL_BEFORE_LOOKING = 0.5  #: seconds a person stands still before the robot reads their arms
#: metres from the person beyond which the head camera sees their arms whole (nearer, a
#: hand held out reads as anything)
_ARMS_IN_VIEW = 0.8
_BURST = 10  #: head-camera frames read as one gesture ...
_BURST_RATE = 10.0  #: ... taken so many a second
_HEAD_TURN = 2.6  #: radians the head turns either way
_PURSUIT = 0.5  #: metres along the path to the point the robot steers for
_PROGRESS = 0.15  #: metres the robot must move on by ...
_STALLED = 2.5  #: ... within so many seconds, or it is stalled ...
_DETOUR = 4.0  #: ... and plans round what it sees for so long
_PURSUIT_TURN = 2.0  #: rad/s of turn per radian off that point
_TURN_ON_THE_SPOT = 0.9  #: radians off it beyond which the robot turns before driving
_DOORWAY_TURN = 0.3  #: ... and on a way square through a doorway
#: radians off that point beyond which a robot whose heading is blocked, but not its way
#: to the point, turns on the spot rather than leave the drive to the local controller
_TURN_FREELY = 0.15
_PURSUIT_SLOWING = 1.5  #: m/s per metre still to go (slowing to a stop at the end)
_PURSUIT_CLEAR = 0.05  #: metres beside the footprint the strip ahead must be free
_PURSUIT_STOPPING = 1.0  #: seconds of driving ahead that must be free
_PASSING = 0.15  #: metres the robot's path keeps from others, beyond its radius
_IN_MY_WAY = 1.5  #: metres of its way ahead on which someone standing blocks a stalled robot
_LET_ME_THROUGH = "Excuse me, could you let me through, please?"
_LOOP_SLACK = 0.5  #: metres farther than its nearest point the trail may be joined, later on
_MOST_PUSHED = 0.25  #: metres a point of the person's trail is moved off a wall, at most
_SEARCH_SHORT = 0.3  #: metres short of where a lost person was heading the robot stops
_SEARCH_TURN = 0.6  #: rad/s the robot turns there, looking round for them


class FollowEnd(StrEnum):
    """Why following ended."""

    STOP_SAID = "stop_said"  #: the person said "stop"
    STOP_SHOWN = "stop_shown"  #: the person showed the stop gesture
    ARRIVED = "arrived"  #: the person stood still where they were going
    LOST = "lost"  #: the robot lost the person and did not find them again
    CANCELLED = "cancelled"
    NOBODY = "nobody"  #: nobody stood in front of the robot to follow


@dataclass(frozen=True, slots=True)
class FollowParameters:
    """How closely the robot follows, and how long it looks for someone lost."""

    distance: float = 1.0  #: metres: the robot stops this far short of the person
    start_reach: float = 2.5  #: metres: the person to follow stands this near at the start
    replan_every: float = 0.5  #: seconds between global paths to the person
    reidentify_gate: float = 0.8  #: metres round the person's predicted spot, at first
    reidentify_growth: float = 1.0  #: metres the gate grows per second lost (a brisk walk)
    reidentify_most: float = 8.0  #: metres the gate grows to at most
    prediction: float = 1.5  #: seconds the person's last velocity is carried on, at most
    give_up: float = 25.0  #: seconds lost before the robot gives up
    still_speed: float = 0.12  #: m/s: a person slower than this stands still
    still_arrived: float = 3.0  #: seconds standing in the goal room: arrived
    still_end: float = 15.0  #: seconds standing anywhere, with no goal room: arrived
    listen_every: float = 0.25  #: seconds between looks at what the microphone heard
    check_every: float = 1.0  #: seconds between looks at what the person followed wears
    mismatches: int = 2  #: looks in a row at other clothes that drop a track
    #: metres between which the head camera sees whoever stands there, head to knees
    camera_reach: tuple[float, float] = (1.0, 3.5)
    budget: float = 600.0  #: seconds: following never lasts longer


@dataclass
class FollowResult:
    """How following went."""

    end: FollowEnd
    travelled: float = 0.0
    last_seen: tuple[float, float] | None = None
    lost_count: int = 0  #: times the person was lost and found again
    seconds: float = 0.0


@dataclass
class _Target:
    """What the robot knows of the person it follows."""

    track_id: int
    position: tuple[float, float]
    velocity: tuple[float, float]
    seen_at: float
    still_since: float | None = None
    others: set[int] = field(default_factory=set)  #: tracks seen beside the person
    dropped: dict[int, float] = field(default_factory=dict)  #: tracks dropped, and when
    wears: str | None = None  #: the colour of their top, as the camera saw it
    trail: list[tuple[float, float]] = field(default_factory=list)  #: where they walked
    mismatches: int = 0  #: looks in a row at the track that showed other clothes
    #: where they stood when the camera last saw nothing wrong with the track followed
    trusted: tuple[float, float] | None = None

    def back_to_trusted(self) -> None:
        """Forget what the track showed since it last looked right: it had slipped onto
        someone or something else."""
        if self.trusted is None:
            return
        self.position, self.velocity = self.trusted, (0.0, 0.0)
        gaps = [math.dist(point, self.trusted) for point in self.trail]
        if gaps:
            del self.trail[int(np.argmin(gaps)) + 1:]


class Following:
    """Follows one person with a body's laser (see the module docstring).

    Args:
        body: the sensors and the base.
        world: the map's rooms (where the person was to lead the robot).
        navigator: stage 1 on the static map.
        controller: stage 2, the local planner.
        localise: the pose estimate after feeding it the latest sensors.
        off_the_map: which of (n, 2) leg positions stand clear of the map's walls and
            furniture (legs near them are the furniture's).
        unexpected: the scan's returns on the map that the static map does not explain
            (people, a chair moved: ``ObstacleMemory.unexpected``); paths to the person
            go round them.
        events: where following is recorded.
        heard_stop: whether the person said stop since the last call (None: deaf).
        stop_shown: whether the person at a map position shows the stop gesture in a burst
            of head-camera frames taken from the poses given
            (``perception.gestures.gesture_from_depth``); None: gestures unseen.
        clothes: what the person the camera sees at a map position wears, from a pose
            (``PeopleLook.clothes_at``; None: no camera, people told apart by the laser
            alone).
        ask_way: says something aloud, to ask someone in the robot's way to let it by
            (None: mute).
    """

    def __init__(self, body: Body, world: World, navigator: Navigator,
                 controller: LocalController, localise: Callable[[], Pose],
                 off_the_map: Callable[[np.ndarray], np.ndarray],
                 unexpected: Callable[[Pose, LaserScan], np.ndarray], events: EventLog, *,
                 heard_stop: Callable[[], bool] | None = None,
                 stop_shown: Callable[[list[RgbdFrame], list[Pose], tuple[float, float]], bool]
                 | None = None,
                 clothes: Callable[[Pose, tuple[float, float]], tuple[str, ...] | None]
                 | None = None,
                 ask_way: Callable[[str], object] | None = None,
                 parameters: FollowParameters | None = None) -> None:
        self.body = body
        self.world = world
        self.navigator = navigator
        self.controller = controller
        self.localise = localise
        self.off_the_map = off_the_map
        self.unexpected = unexpected
        self.events = events
        self.heard_stop = heard_stop
        self.stop_shown = stop_shown
        self.clothes = clothes
        self.ask_way = ask_way
        self._asked: set[int] = set()  #: tracks asked to let the robot by
        self.parameters = parameters or FollowParameters()
        self.tracker = PeopleTracker()
        #: head-camera frames of the person standing still, and the poses they were taken from
        self._burst: list[tuple[RgbdFrame, Pose]] = []
        self._intrinsics: CameraIntrinsics | None = None  #: the head camera's, once seen

    # ------------------------------------------------------------ the loop

    def follow(self, goal_room: str | None = None, *,
               cancel: CancelToken | None = None,
               person_near: tuple[float, float] | None = None) -> FollowResult:
        """Follow the person in front (nearest ``person_near`` when given) until they say
        stop, stand still where they were going, or are lost."""
        p = self.parameters
        body = self.body
        started = body.now()
        target = self._first_sight(person_near)
        if target is None:
            return FollowResult(FollowEnd.NOBODY)
        self.events.record("robot.following", track=target.track_id,
                           at=[round(v, 2) for v in target.position])
        result = FollowResult(FollowEnd.LOST, last_seen=target.position)
        path: list[tuple[float, float]] = []
        planned_at = -math.inf
        listened_at = checked_at = body.now()
        lost_since: float | None = None
        last_odometry = body.odometry().pose
        progress = (body.now(), self.localise().xy())  # when the robot last moved on, where
        detour_until = -math.inf
        while True:
            now = body.now()
            if cancel is not None and cancel.cancelled:
                result.end = FollowEnd.CANCELLED
                break
            if now - started > p.budget:
                result.end = FollowEnd.LOST
                break
            pose = self.localise()
            seen = self._sense(pose, target)
            if seen:
                if lost_since is not None:
                    self.events.record("robot.following_found", track=target.track_id,
                                       lost_for=round(now - lost_since, 2))
                    result.lost_count += 1
                    lost_since = None
                    planned_at = -math.inf
                result.last_seen = target.position
            elif lost_since is None and now - target.seen_at > self.tracker.parameters.coast:
                lost_since = target.seen_at
                self.events.record("robot.following_lost", track=target.track_id,
                                   at=[round(v, 2) for v in target.position])
            if lost_since is not None and now - lost_since > p.give_up:
                result.end = FollowEnd.LOST
                break
            if seen and now - checked_at >= p.check_every:
                checked_at = now
                if not self._looks_right(pose, target):
                    self.events.record("robot.following_dropped", track=target.track_id)
                    target.dropped[target.track_id] = now
                    target.back_to_trusted()
                    target.track_id = -1
                    target.seen_at = now - self.tracker.parameters.coast
            if now - listened_at >= p.listen_every:
                listened_at = now
                if self.heard_stop is not None and self.heard_stop():
                    result.end = FollowEnd.STOP_SAID
                    break
            if seen and self._shows_stop(pose, target, now):
                result.end = FollowEnd.STOP_SHOWN
                break
            if seen and self._arrived(target, goal_room, now):
                result.end = FollowEnd.ARRIVED
                break
            aim = self._aim(target, now)
            if math.dist(pose.xy(), progress[1]) > _PROGRESS or \
                    math.dist(pose.xy(), aim) <= p.distance + _PROGRESS:
                progress = (now, pose.xy())
            elif now - progress[0] > _STALLED:
                # the person's own way is too tight for the robot here (someone sits
                # beside it): ask whoever stands in the way to let it by, and plan round
                # what the laser sees for a while
                self._ask_way(self._their_way(pose, target) or path or [pose.xy(), aim],
                              target)
                detour_until, progress, path = now + _DETOUR, (now, pose.xy()), []
                self.events.record("robot.following_detour")
            if now - planned_at >= p.replan_every or not path:
                path = self._path_to(pose, aim, target, trail=now >= detour_until)
                planned_at = now
            body.command_velocity(self._command(pose, aim, path, seen))
            body.tick()
            odometry = body.odometry().pose
            result.travelled += math.dist(odometry.xy(), last_odometry.xy())
            last_odometry = odometry
        self._stop_base()
        result.seconds = round(body.now() - started, 3)
        result.travelled = round(result.travelled, 3)
        self.events.record("robot.followed", end=result.end.value, lost=result.lost_count,
                           travelled=result.travelled)
        return result

    # ------------------------------------------------------------ tracking

    def _first_sight(self, near: tuple[float, float] | None) -> _Target | None:
        """Watch a second standing still; the confirmed track nearest ``near`` (else the
        nearest in front of the robot) within reach."""
        body = self.body
        body.command_velocity(Twist())
        pose = self.localise()
        for _ in range(max(1, round(1.0 / body.tick_period))):
            body.tick()
            self._update_tracker(self.localise())
        reach = self.parameters.start_reach
        here = pose.xy()
        centre = near or here
        candidates = [track for track in self.tracker.confirmed()
                      if math.dist(track.position, here) <= reach + (
                          0.0 if near is None else 1.0)]
        if near is None:
            candidates = [track for track in candidates if abs(wrap_angle(math.atan2(
                track.position[1] - pose.y, track.position[0] - pose.x) - pose.theta))
                <= math.pi / 2]
        if not candidates:
            return None
        chosen = min(candidates, key=lambda track: math.dist(track.position, centre))
        target = _Target(chosen.id, chosen.position, chosen.velocity, body.now(),
                         others={track.id for track in candidates if track.id != chosen.id})
        if self.clothes is not None:
            wears = self.clothes(self.localise(), chosen.position)
            target.wears = wears[0] if wears and wears != UNREAD else None
        return target

    def _their_way(self, pose: Pose, target: _Target) -> list[tuple[float, float]] | None:
        """The way the person walked on from where it passes nearest the robot (None: the
        robot is not near it)."""
        walked = target.trail
        if not walked:
            return None
        gaps = np.hypot(*(np.asarray(walked) - np.asarray(pose.xy())).T)
        nearest = int(np.argmin(gaps))
        return [pose.xy(), *walked[nearest:]] if gaps[nearest] <= _ON_THE_TRAIL else None

    def _ask_way(self, path: list[tuple[float, float]], target: _Target) -> None:
        """Ask someone standing on ``path`` just ahead (the person's own way, where the
        robot cannot pass them; not the person followed), once each, to let it through."""
        if self.ask_way is None:
            return
        ahead = [found[0] for metres in np.arange(0.0, _IN_MY_WAY, 0.1)
                 if (found := point_along(path, float(metres))) is not None]
        if not ahead:
            return
        reach = self.body.radius + _OWN_LEGS
        for track in self.tracker.confirmed():
            if track.id == target.track_id or track.id in self._asked or \
                    math.dist(track.position, target.position) <= _OWN_LEGS:
                continue
            if min(math.dist(track.position, point) for point in ahead) <= reach:
                self._asked.add(track.id)
                self.events.record("robot.following_asked_way", track=track.id)
                self._stop_base()  # the body's clock runs while it speaks
                self.ask_way(_LET_ME_THROUGH)
                return

    def _update_tracker(self, pose: Pose) -> list[Track]:
        scan = self.body.scan()
        legs = detect_legs(scan, pose)
        if len(legs):
            legs = legs[self.off_the_map(legs)]
        return self.tracker.update(self.body.now(), legs, scan, pose)

    def _sense(self, pose: Pose, target: _Target) -> bool:
        """Update the tracker; whether the person was seen this sweep (their track, or a
        new one where they would be)."""
        p = self.parameters
        now = self.body.now()
        confirmed = self._update_tracker(pose)
        mine = next((track for track in self.tracker.tracks if track.id == target.track_id),
                    None)
        if mine is not None and mine.seen >= now - 1e-9:
            self._take(target, mine, now)
            target.others.update(track.id for track in confirmed
                                 if track.id != mine.id and
                                 math.dist(track.position, mine.position) > _SURELY_SOMEONE_ELSE)
            return True
        if mine is not None and mine.confirmed:
            return False  # coasting: hidden for a moment
        lost_for = now - target.seen_at
        gate = min(p.reidentify_most, p.reidentify_gate + p.reidentify_growth * lost_for)
        predicted = self._predicted(target, now)
        candidates = [track for track in confirmed
                      if now - target.dropped.get(track.id, -math.inf) > _DROPPED_FOR
                      and track.seen >= now - 1e-9
                      and math.dist(track.position, predicted) <= gate]
        for chosen in sorted(candidates, key=lambda track: math.dist(track.position, predicted)):
            if self._needs_clothes(target, chosen, predicted):
                # only the camera, seeing the person's clothes, can tell
                if not self._wears_same(pose, target, chosen.position):
                    continue
            elif self._wears_other(pose, target, chosen.position):
                target.others.add(chosen.id)
                continue
            target.track_id, target.mismatches = chosen.id, 0
            target.still_since = None  # how long someone stands is their own track's
            self._take(target, chosen, now)
            return True
        return False

    def _needs_clothes(self, target: _Target, track: Track,
                       predicted: tuple[float, float]) -> bool:
        """Whether ``track`` is taken for the person lost only when the camera sees their
        clothes on it: it was taken for someone else while the robot followed a track
        that had slipped onto them, or it was dropped for showing other clothes, or it
        stands still far from where the person, walking, was heading (someone standing
        there all along: a passer-by at the end of their crossing)."""
        if track.id in target.others or track.id in target.dropped:
            return True
        walking = math.hypot(*target.velocity) >= self.parameters.still_speed
        still = math.hypot(*track.velocity) < self.parameters.still_speed
        return walking and still and math.dist(track.position, predicted) > _STOPPED_NEAR

    def _wears_other(self, pose: Pose, target: _Target, where: tuple[float, float]) -> bool:
        """Whether the camera sees nobody at ``where``, or someone dressed unlike the
        person followed (False when it cannot tell: no camera, out of the head's turn,
        someone nearer in the way, clothes unread)."""
        if self.clothes is None or self._hidden(pose, where):
            return False
        wears = self.clothes(pose, where)
        if wears is None:
            return False
        if not wears:
            return self.parameters.camera_reach[0] <= math.dist(where, pose.xy()) <= \
                self.parameters.camera_reach[1]
        return target.wears is not None and wears != UNREAD and wears[0] != target.wears

    def _wears_same(self, pose: Pose, target: _Target, where: tuple[float, float]) -> bool:
        """Whether the camera sees someone dressed like the person followed at ``where``,
        nobody standing in the way."""
        if self.clothes is None or target.wears is None or self._hidden(pose, where):
            return False
        wears = self.clothes(pose, where)
        return wears is not None and wears != UNREAD and len(wears) > 0 and \
            wears[0] == target.wears

    def _hidden(self, pose: Pose, where: tuple[float, float]) -> bool:
        """Whether someone the laser tracks stands between the robot and ``where``, or
        right beside it (the camera would see them, or could not tell them apart from
        whoever stands there)."""
        here = np.asarray(pose.xy())
        sight = np.asarray(where) - here
        length = float(np.hypot(*sight))
        for track in self.tracker.confirmed():
            beside = math.dist(track.position, where)
            if beside <= _OWN_LEGS / 3:
                continue  # the one at ``where``
            if beside <= _SIDE_BY_SIDE:
                return True
            if length < 1e-6:
                continue
            offset = np.asarray(track.position) - here
            along = float(offset @ sight) / length
            across = abs(float(sight[0] * offset[1] - sight[1] * offset[0])) / length
            if 0.0 < along < length and across < _IN_THE_WAY:
                return True
        return False

    def _looks_right(self, pose: Pose, target: _Target) -> bool:
        """Look at the track followed: False once it showed nobody, or other clothes,
        ``mismatches`` times in a row (it slipped onto someone or something else)."""
        if self._wears_other(pose, target, target.position):
            target.mismatches += 1
        else:
            target.mismatches = 0
            target.trusted = target.position
        return target.mismatches < self.parameters.mismatches

    def _take(self, target: _Target, track: Track, now: float) -> None:
        moving = math.hypot(*track.velocity) >= self.parameters.still_speed
        if moving:
            target.still_since = None
        elif target.still_since is None:
            target.still_since = now
        target.position, target.velocity, target.seen_at = track.position, track.velocity, now
        if not target.trail:
            target.trail.append(track.position)
        elif math.dist(target.trail[-1], track.position) >= _TRAIL_STEP:
            target.trail.extend(self._bridged(target.trail[-1], track.position))

    def _bridged(self, last: tuple[float, float], seen: tuple[float, float]
                 ) -> list[tuple[float, float]]:
        """The trail's points from ``last`` on to ``seen``, where the person was found
        again after being hidden: the straight line between them where the robot fits
        along it, else the map's way round (a door frame or a corner stands between
        them; the straight line led the robot into the jamb)."""
        if math.dist(last, seen) <= _TRAIL_GAP or \
                self._in_sight(last, seen, self.body.radius + _PASSING):
            return [seen]
        plan = self.navigator.plan(last, seen)
        if plan is None:
            return [seen]
        way = [(float(x), float(y)) for x, y in plan.waypoints]
        way[-1] = seen
        steps = max(1, math.ceil(polyline_length(way) / _TRAIL_STEP))
        points = [found[0] for index in range(1, steps)
                  if (found := point_along(way, index * _TRAIL_STEP)) is not None]
        return [*points, seen]

    def _predicted(self, target: _Target, now: float) -> tuple[float, float]:
        ahead = min(self.parameters.prediction, now - target.seen_at)
        return (target.position[0] + target.velocity[0] * ahead,
                target.position[1] + target.velocity[1] * ahead)

    def _shows_stop(self, pose: Pose, target: _Target, now: float) -> bool:
        """Whether the person, standing still and turned to the robot, shows the stop
        gesture: once they stood still a moment, the head camera takes a burst of frames
        of them (``_BURST`` at ``_BURST_RATE``), read as a whole."""
        if self.stop_shown is None or target.still_since is None or \
                now - target.still_since < _STILL_BEFORE_LOOKING or \
                not _ARMS_IN_VIEW <= math.dist(pose.xy(), target.position) \
                <= self.parameters.camera_reach[1]:
            self._burst.clear()
            return False
        if self._burst and now - self._burst[-1][0].stamp < 1.0 / _BURST_RATE - 1e-6:
            return False
        bearing = wrap_angle(math.atan2(target.position[1] - pose.y,
                                        target.position[0] - pose.x) - pose.theta)
        # tilted up so that a hand held up stays in the picture, however near they stand
        tilt = 0.0 if self._intrinsics is None else \
            looking_tilt(math.dist(pose.xy(), target.position), self._intrinsics)
        self.body.point_head(max(-_HEAD_TURN, min(_HEAD_TURN, bearing)), tilt)
        try:
            frame = self.body.camera()
        except PartMissing:
            self.stop_shown = None
            return False
        if self._intrinsics is None:  # the first frame shows what the camera sees
            self._intrinsics = frame.intrinsics
            return False
        self._burst.append((frame, pose))
        if len(self._burst) < _BURST:
            return False
        frames, poses = zip(*self._burst, strict=True)
        self._burst.clear()
        # a track that slipped onto someone else (a seated person with a hand up, passed
        # close by) shows their gesture, not the person's: their clothes tell
        return self.stop_shown(list(frames), list(poses), target.position) and \
            not self._wears_other(pose, target, target.position)

    def _arrived(self, target: _Target, goal_room: str | None, now: float) -> bool:
        if target.still_since is None:
            return False
        still = now - target.still_since
        if goal_room is not None:
            return still >= self.parameters.still_arrived and \
                self.world.room_at(*target.position) == goal_room
        return still >= self.parameters.still_end

    # ------------------------------------------------------------ driving

    def _aim(self, target: _Target, now: float) -> tuple[float, float]:
        """Where to drive: to the person while seen; where they were last heading when
        not (round the corner they turned)."""
        return target.position if now - target.seen_at < 0.5 else self._predicted(target, now)

    def _path_to(self, pose: Pose, aim: tuple[float, float], target: _Target, *,
                 trail: bool = True) -> list[tuple[float, float]]:
        """The way the person walked (their trail, from where it passes nearest the
        robot), which is free and goes through doorways where people do, and on from its
        end to where they were heading when the robot lost them. Where the robot has
        strayed from the trail, a path planned round what the laser sees that the map
        lacks (others on the way), but for the person themself."""
        here = pose.xy()
        walked = target.trail
        if walked and trail:
            gaps = np.hypot(*(np.asarray(walked) - np.asarray(here)).T)
            nearest = int(np.argmin(gaps))
            if gaps[nearest] <= _ON_THE_TRAIL:
                # where the person came back past the robot (a way back, a loop), their
                # trail is joined where it last passes near, not driven round
                near = np.flatnonzero(gaps <= gaps[nearest] + _LOOP_SLACK)
                nearest = next((int(index) for index in near[::-1]
                                if self._in_sight(here, walked[int(index)])), nearest)
                del walked[:nearest]
                # on to the point after the nearest, or to the nearest first where the
                # straight way to the one after it is blocked (a trail that jumps on past
                # a door frame, where the person was found again)
                ahead = walked[1:] if len(walked) < 2 or self._in_sight(here, walked[1]) \
                    else walked
                path = [here, *self._off_the_walls(ahead)]
                if aim != target.position:
                    plan = self.navigator.plan(path[-1], aim)
                    path.extend(plan.waypoints[1:] if plan is not None else [aim])
                return self._through_doorways(path) if len(path) > 1 else [here, aim]
        obstacles = self.unexpected(pose, self.body.scan())
        if len(obstacles):
            obstacles = obstacles[np.hypot(*(obstacles - np.asarray(aim)).T) > _OWN_LEGS]
        way = self.navigator.plan_around(here, aim, frozenset(), obstacles,
                                         self.body.radius + _PASSING, near_goal=_OWN_LEGS)
        if way is not None:
            return list(way)
        plan = self.navigator.plan(here, aim)
        if plan is None:
            return [here, aim]
        return [tuple(point) for point in plan.waypoints]  # type: ignore[misc]

    def _in_sight(self, start: tuple[float, float], end: tuple[float, float],
                  clearance: float | None = None) -> bool:
        """Whether the robot's body (or a disc of ``clearance`` metres) fits along the
        straight line between two points, by the map's walls and furniture."""
        navigator = self.navigator
        needed = self.body.radius if clearance is None else clearance
        steps = max(1, math.ceil(math.dist(start, end) / navigator.grid.resolution))
        return all(navigator.clearance_at(start[0] + t * (end[0] - start[0]),
                                          start[1] + t * (end[1] - start[1]))
                   >= needed for t in np.linspace(0.0, 1.0, steps + 1))

    def _off_the_walls(self, points: list[tuple[float, float]]) -> list[tuple[float, float]]:
        """The points of a person's trail moved off the map's walls and furniture to where
        the robot's body keeps ``_PASSING`` clear of them, as far as the floor allows (a
        person walks closer to a wall than the robot fits; a doorway's middle stays put)."""
        clear_at = self.navigator.clearance_at
        step = self.navigator.grid.resolution
        needed = self.body.radius + _PASSING
        moved = []
        for x, y in points:
            short = needed - clear_at(x, y)
            if short > 0.0:
                gradient = ((clear_at(x + step, y) - clear_at(x - step, y)) / (2 * step),
                            (clear_at(x, y + step) - clear_at(x, y - step)) / (2 * step))
                norm = math.hypot(*gradient)
                if norm > 0.5:  # a clear way off the wall (not a doorway's middle)
                    push = min(short, _MOST_PUSHED) / norm
                    x, y = x + push * gradient[0], y + push * gradient[1]
            moved.append((x, y))
        return moved

    def _through_doorways(self, path: list[tuple[float, float]]) -> list[tuple[float, float]]:
        """``path`` up to the first doorway it goes through, crossed square: the points
        near the doorway replaced by one in front of it, its middle and one beyond, where
        the path then ends (a trail that crosses a doorway at a slant, or turns right
        after it, leads the robot into the jamb). The robot stops short of the person
        only on a path that ends at them (``_DoorwayPath`` marks one that does not)."""
        world = self.world
        leaving = self._out_of_doorway(path)
        if leaving is not None:
            return leaving
        crossings = []
        for name, door in world.doors.items():
            inside = [index for index, point in enumerate(path)
                      if math.dist(point, door.position) <= _DOORWAY_REACH]
            if not inside:
                continue
            first, last = inside[0], inside[-1]
            # the robot itself near the doorway: its side of the wall is where it stands
            before = world.room_at(*path[first - 1]) if first > 0 else \
                self._side_of(name, path[0])
            after = world.room_at(*path[min(last + 1, len(path) - 1)])
            if before is not None and after is not None and before != after and \
                    before in door.rooms and after in door.rooms:
                crossings.append((first, name, before, after))
        if not crossings:
            return path
        first, name, before, after = min(crossings)
        square = [world.point_before_door(name, room, _DOORWAY_REACH).xy()
                  for room in (before, after)]
        middle = world.doors[name].position
        if first == 0:
            # from beside the doorway: onto its axis first, as far out as the robot stands
            # (unless it stands on it already, or fits straight into the doorway)
            normal = world.door_normal(name)
            across, along = self._off_door(name, path[0])
            out = math.copysign(max(abs(across), _IN_THE_FRAME), across)
            axis = (middle[0] + out * normal[0], middle[1] + out * normal[1])
            straight = along <= _ON_THE_AXIS or \
                self._in_sight(path[0], middle, self.body.radius + _PURSUIT_CLEAR)
            start = [path[0]] if straight else [path[0], axis]
            return _DoorwayPath([*start, middle, square[1]])
        return _DoorwayPath([*path[:first], square[0], middle, square[1]])

    def _side_of(self, door: str, point: tuple[float, float]) -> str:
        """The room of ``door``'s two on whose side of its wall ``point`` lies."""
        rooms = self.world.doors[door].rooms
        return rooms[0] if self._off_door(door, point)[0] >= 0.0 else rooms[1]

    def _off_door(self, door: str, point: tuple[float, float]) -> tuple[float, float]:
        """How far ``point`` lies from ``door``'s middle across its wall (signed, positive
        into the door's first room) and along it (unsigned), metres."""
        x, y = self.world.doors[door].position
        normal = self.world.door_normal(door)
        offset = (point[0] - x, point[1] - y)
        return (offset[0] * normal[0] + offset[1] * normal[1],
                abs(offset[0] * normal[1] - offset[1] * normal[0]))

    def _out_of_doorway(self, path: list[tuple[float, float]]) -> _DoorwayPath | None:
        """Where the robot stands in a doorway's frame: straight out of it, to the point
        ``_DOORWAY_REACH`` in front of it on the side ``path`` leaves it by (from inside
        the frame the way on to the person turns at a slant into the jamb); None when the
        robot stands in no doorway, or the person stands just out of it."""
        here = path[0]
        for name, door in self.world.doors.items():
            across, along = self._off_door(name, here)
            if abs(across) > _IN_THE_FRAME or along > door.width / 2:
                continue
            out = next((point for point in path[1:]
                        if math.dist(point, door.position) > _DOORWAY_REACH), path[-1])
            side = 1.0 if self._off_door(name, out)[0] >= 0.0 else -1.0
            normal = self.world.door_normal(name)
            beyond = (door.position[0] + side * _DOORWAY_REACH * normal[0],
                      door.position[1] + side * _DOORWAY_REACH * normal[1])
            if math.dist(beyond, path[-1]) < self.parameters.distance:
                return None  # the person stands just out there: come up to them
            return _DoorwayPath([here, beyond])
        return None

    def _command(self, pose: Pose, aim: tuple[float, float],
                 path: list[tuple[float, float]], seen: bool) -> Twist:
        """Drive along ``path`` to ``distance`` short of its end and there turn to face
        the person; not seeing them, drive on to where they were heading, and there
        turn round, looking for them."""
        body = self.body
        short = path if isinstance(path, _DoorwayPath) else \
            shortened(path, self.parameters.distance if seen else _SEARCH_SHORT)
        if short is None:
            if not seen:
                return Twist(0.0, 0.0, _SEARCH_TURN)
            bearing = wrap_angle(math.atan2(aim[1] - pose.y, aim[0] - pose.x) - pose.theta)
            turn = max(-body.limits.angular, min(body.limits.angular, 1.5 * bearing))
            return Twist(0.0, 0.0, turn if abs(bearing) > 0.15 else 0.0)
        pursued = self._pursue(pose, short)
        if pursued is not None:
            return pursued
        return self.controller.plan(pose, body.odometry().twist, body.scan(), short,
                                    body.limits, body.drive, body.radius)

    def _pursue(self, pose: Pose, path: list[tuple[float, float]]) -> Twist | None:
        """Pure pursuit of a point a short way along ``path`` (which runs where the person
        walked, or square through a doorway): turn on the spot towards it when it lies
        well off the heading, else drive at it, slowing near the path's end; where the strip
        the base would drive through is blocked but the strip towards that point is
        free, turn on the spot. None when something stands in both (the local controller
        then steers round it)."""
        body = self.body
        found = point_along(path, _PURSUIT)
        target = found[0] if found is not None else path[-1]
        remaining = polyline_length(path)
        error = wrap_angle(math.atan2(target[1] - pose.y, target[0] - pose.x) - pose.theta)
        limits = body.limits
        turn = max(-limits.angular, min(limits.angular, _PURSUIT_TURN * error))
        # square through a doorway: an arc into it meets the jamb
        if abs(error) > (_DOORWAY_TURN if isinstance(path, _DoorwayPath) else _TURN_ON_THE_SPOT):
            return Twist(0.0, 0.0, turn)
        speed = min(limits.linear, _PURSUIT_SLOWING * remaining) * math.cos(error)
        ahead = body.radius + _PURSUIT_CLEAR + speed * _PURSUIT_STOPPING
        points = body.scan().points()
        width = body.radius + _PURSUIT_CLEAR
        if len(points) and _in_strip(points, ahead, width):
            # the heading is blocked but the way to the point steered for is free (a wall
            # beside a turn, the robot's arc too wide): turn towards it first
            cos, sin = math.cos(error), math.sin(error)
            towards = np.column_stack((points[:, 0] * cos + points[:, 1] * sin,
                                       points[:, 1] * cos - points[:, 0] * sin))
            reach = min(ahead, math.dist(pose.xy(), target) + width)
            if abs(error) > _TURN_FREELY and not _in_strip(towards, reach, width):
                return Twist(0.0, 0.0, turn)
            return None
        return Twist(speed, 0.0, turn)

    def _stop_base(self) -> None:
        body = self.body
        body.command_velocity(Twist())
        for _ in range(60):
            if body.odometry().twist.is_zero():
                break
            body.tick()


def _in_strip(points: np.ndarray, length: float, half_width: float) -> bool:
    """Whether any of ``points`` (n, 2), in the robot's frame, lies in the strip
    ``length`` metres straight ahead of it and ``half_width`` either side."""
    return bool(((points[:, 0] > 0.0) & (points[:, 0] < length) &
                 (np.abs(points[:, 1]) < half_width)).any())


class _DoorwayPath(list[tuple[float, float]]):
    """A path that ends beyond a doorway, not at the person: driven to its end."""


def shortened(path: list[tuple[float, float]], by: float
               ) -> list[tuple[float, float]] | None:
    """``path`` without its last ``by`` metres (None: it is no longer than that)."""
    left = by
    points = list(path)
    while len(points) >= 2:
        (x0, y0), (x1, y1) = points[-2], points[-1]
        length = math.hypot(x1 - x0, y1 - y0)
        if length > left:
            t = (length - left) / length
            points[-1] = (x0 + t * (x1 - x0), y0 + t * (y1 - y0))
            return points if math.dist(points[0], points[-1]) > 0.05 or len(points) > 2 \
                else None
        left -= length
        points.pop()
    return None

