"""``BodyRobot``: the Robot port over a ``Body``, with the action/perception layer between.

The robot localises itself with Monte Carlo localisation from its odometry and
laser, plans a global path on the static map (stage 1) and drives it with a
reactive local planner on the live scan (stage 2). ``pose`` is the estimate,
never the truth, so a navigate monitor can find the robot is not where it
meant to be. A route goes door by door: the robot stops in front of each door,
looks whether it is open and whether someone stands in it, and reports a shut
or blocked door so the executive's door protocol can act.

Objects on placements are seen with the head camera through the table-top
pipeline (``looking``); people with the laser, the head camera and faces
(``people_look``); whether a door is open by whether the laser's beams pass
through the doorway (``doors``). The robot speaks through the body's speaker and
hears answers in its microphone (``conversation``). It holds nothing of the simulator:
everything it believes comes through the ``Body`` port. Hands are the arm's
(``ArmedBodyRobot``, ``homebot.embodied.hands``); a ``BodyRobot`` alone has none.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from shapely.geometry import LineString
from shapely.geometry import Point as ShapelyPoint

from homebot.cancel import CancelToken
from homebot.embodied.conversation import Conversation
from homebot.embodied.doors import WayThrough, door_seen_open, leaf_barely_ajar, way_through
from homebot.embodied.following import FollowEnd, Following, FollowParameters, shortened
from homebot.embodied.guiding import Guiding
from homebot.embodied.looking import TableLook
from homebot.embodied.people_look import PeopleLook
from homebot.errors import NavigationError, PartMissing
from homebot.events import EventLog
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.localisation import MonteCarloLocalisation
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigate import StopReason
from homebot.navigation.recovery import RecoveringNavigation, scan_on_map
from homebot.navigation.straight import drive_straight
from homebot.perception.faces import Acquaintances
from homebot.perception.gestures import gesture_from_depth
from homebot.robot import (
    Blocker,
    Body,
    Detection,
    HelpRequest,
    MoveReport,
    PersonPercept,
    RgbdFrame,
    Robot,
    Twist,
)
from homebot.world import PlacementKind, World

if TYPE_CHECKING:
    from homebot.speech.answers import AnswerRecognizer
    from homebot.speech.recognizer import Hearing

#: the dialogue state in which "stop" is heard (``homebot.speech.answers.STOP``; named here
#: so that the speech extra loads only when the robot first listens)
STOP = "stop"
_STOP_WORDS = frozenset({"stop", "halt"})  #: the words that end following on their own
_NO = frozenset({"no", "nope", "not", "wrong"})  #: first words of a refusal

__all__ = ["BodyRobot"]

_STOP_BEFORE_DOOR = 0.6  #: metres in front of a door where the robot stops to look at it
_SEES_THE_DOOR = 3.0  #: metres within which the robot, stopped short, looks at a door ahead
_FURNITURE_NEAR_DOOR = 1.5  #: metres from a door within which the map's furniture counts
_OUTLINE_STEP = 0.02  #: metres between the points taken along a furniture's outline
_CLOSE_TO_THE_DOOR = 1.3  #: metres from a door's middle: near enough to look at it and pass
_NEAR_THE_DOOR = 0.5  #: metres: a door's leaf on the spot before it, this near will do
_WATCH_DOORWAY = 6.0  #: seconds the robot watches a doorway someone stands in before it asks
_WATCH_EVERY = 0.5  #: seconds between its looks at the doorway meanwhile
_ON_THE_WAY = 0.1  #: metres from a way's entry where the robot may start along it
_GOAL_TOLERANCE = 0.15  #: metres: a leg ends this close to its end point
_HEADING_TOLERANCE = 0.2  #: radians: the final turn ends this close to the goal's heading
_PARTICLES_SHOWN = 500
_IN_THE_WAY = 0.8  #: metres from the robot's way within which a person stands in it
_FOLLOWING_REACH = 2.0  #: metres within which the person to follow must stand
_ASKING_DISTANCE = 1.2  #: metres from a person where the robot stops to ask them something
_COMING_UP = (_ASKING_DISTANCE, 0.9, 0.7)  #: metres short of someone the robot comes up to
_INTRODUCTION_VIEWS = 20  #: face views enrolled while a person says their name (2 s at 10 Hz)
_RECOGNITION_VIEWS = 10  #: face views weighed together to name the person in front


@dataclass(frozen=True, slots=True)
class _Leg:
    """One stretch of a route: to a point in front of a door, or to the goal."""

    target: Pose
    door: str | None  #: the door the robot stands before at the end, if any


class BodyRobot(Robot):
    """A robot that drives its body through localisation and two-stage navigation.

    Args:
        body: the drivers.
        world: the map and the names of places (what the robot was told, not the truth).
        navigator: stage 1, on the static map.
        localisation: the particle filter, already initialised (or left for a global start).
        controller: stage 2, the local planner.
        events: where the robot's laser, particles and motions are recorded (it never
            reads them).
        looking: sees objects on placements with the head camera and the table-top
            pipeline.
        conversation: speaks and hears through the body (default: answers heard by an
            ``AnswerRecognizer`` for ``world``, built on the first question).
    """

    def __init__(self, body: Body, world: World, navigator: Navigator,
                 localisation: MonteCarloLocalisation, controller: LocalController,
                 events: EventLog, *, looking: TableLook | None = None,
                 conversation: Conversation | None = None) -> None:
        self.body = body
        self.world = world
        self.navigator = navigator
        self.localisation = localisation
        self.controller = controller
        self.events = events
        self.looking = looking
        self.conversation = conversation or Conversation(body, events,
                                                         lambda: _answer_recogniser(world))
        #: whether a person shows the stop gesture now (``homebot.perception.gestures``
        #: over their arm keypoints); follow and guide stop when the person they walk
        #: with does. None: nobody's gestures are seen.
        self.stop_shown: Callable[[str], bool] | None = None
        #: the people met by name ("my name is ...") (``introduce``, ``face_in_front``).
        #: None: faces unseen.
        self.acquaintances: Acquaintances | None = None
        #: sees people with the laser and the head camera (None: ``percepts`` answers,
        #: symbolically)
        self.people_look: PeopleLook | None = None
        self._walking_with: str | None = None
        self.navigation = RecoveringNavigation(body, navigator, controller, self.localise,
                                               on_replan=self._record_replan)
        self.localisation.update(body.odometry(), body.scan())

    # ------------------------------------------------------------ state

    @property
    def hands(self) -> tuple[str, ...]:
        return tuple(self.world.robot.hands)

    def now(self) -> float:
        return self.body.now()

    def pose(self) -> Pose:
        return self.localisation.estimate()

    def localise(self) -> Pose:
        """Feed the filter the latest odometry and scan; the estimate."""
        return self.localisation.update(self.body.odometry(), self.body.scan())

    # ------------------------------------------------------------ motion

    def move_to(self, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *,
                cancel: CancelToken | None = None) -> MoveReport:
        if escort is not None and self.people_look is not None:
            # leading someone: in stretches, looking back for them (``embodied.guiding``)
            return Guiding(self).guide(escort, goal, avoid_doors, cancel=cancel)
        start = self.pose()
        plan = self.navigator.plan(start.xy(), goal.xy(), avoid_doors)
        if plan is None:
            return MoveReport(False, start, 0.0, Blocker.NO_PATH)
        legs = [_Leg(self.world.point_before_door(door, plan.route.rooms[index],
                                                  _STOP_BEFORE_DOOR), door)
                for index, door in enumerate(plan.doors)]
        legs.append(_Leg(goal, None))
        travelled = 0.0
        passed: list[str] = []
        companion = escort or self._walking_with
        for index, leg in enumerate(legs):
            report = self._drive_leg(leg.target, avoid_doors, final=leg.door is None,
                                     companion=companion, cancel=cancel,
                                     near_enough=_NEAR_THE_DOOR if leg.door else 0.0)
            travelled += report.distance
            if report.blocker is Blocker.CANCELLED:
                return MoveReport(False, self.pose(), travelled, Blocker.CANCELLED,
                                  doors_passed=tuple(passed))
            if not report.reached and leg.door is not None and \
                    report.blocker in (Blocker.OBSTRUCTED, Blocker.PERSON) and \
                    math.dist(self.pose().xy(), self.world.doors[leg.door].position) <= \
                    _CLOSE_TO_THE_DOOR and self._door_blocker(leg.door) is None:
                # Kept off the spot before the door (a leaf swung towards the robot, seen
                # end on, looks like someone's leg), but close to it, and it is open with
                # a way through: go on through.
                report = MoveReport(True, self.pose(), report.distance)
            if not report.reached:
                self._record_view()
                # Stopped short: a door still ahead that is shut, or that the laser sees
                # someone (or something) stand in, is what keeps the robot out.
                ahead = self._door_ahead_blocked(legs[index:])
                if ahead is not None and ahead[1] is Blocker.PERSON and \
                        ahead[0] == leg.door and self._doorway_clears(leg.door, avoid_doors):
                    report = MoveReport(True, self.pose(), report.distance)  # on through it
                elif ahead is not None:
                    door, blocker, person = ahead
                    self.events.record("robot.blocked", door=door, blocker=blocker.value)
                    return MoveReport(False, self.pose(), travelled, blocker, door, person,
                                      tuple(passed))
                else:
                    return MoveReport(False, self.pose(), travelled, report.blocker,
                                      report.door, report.person, tuple(passed))
            if leg.door is not None:
                blocked = self._door_blocker(leg.door)
                if blocked is not None and blocked[0] is Blocker.PERSON and \
                        self._doorway_clears(leg.door, avoid_doors):
                    blocked = None
                if blocked is not None:
                    self._record_view()
                    self.events.record("robot.blocked", door=leg.door, blocker=blocked[0].value)
                    return MoveReport(False, self.pose(), travelled, blocked[0], leg.door,
                                      blocked[1], tuple(passed))
                travelled += self._pass_narrow_doorway(leg.door, avoid_doors)
                passed.append(leg.door)
        self._record_view()
        return MoveReport(True, self.pose(), travelled, doors_passed=tuple(passed))

    def move_with(self, companion: str, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                  *, cancel: CancelToken | None = None) -> MoveReport:
        """``move_to`` ``goal`` with ``companion`` walking along (a stretch of guiding them):
        the motion stops when they show stop (``stop_shown``)."""
        self._walking_with = companion
        try:
            return self.move_to(goal, avoid_doors, cancel=cancel)
        finally:
            self._walking_with = None

    def _drive_leg(self, target: Pose, avoid_doors: frozenset[str], final: bool,
                   companion: str | None = None, cancel: CancelToken | None = None,
                   near_enough: float = 0.0) -> MoveReport:
        """Drive to ``target`` along stage-1 paths, planning round what blocks the way;
        stop when ``companion`` (the person guided or followed) shows stop, or when
        ``cancel`` is cancelled. Something standing on ``target``: as near as there is
        room, within ``near_enough`` metres, will do."""
        shown = self.stop_shown
        gesture = (lambda: shown(companion)) if shown is not None and companion else None

        def stop() -> bool:
            return (cancel is not None and cancel.cancelled) or (
                gesture is not None and gesture())

        try:
            attempt = self.navigation.drive(target, avoid_doors, tolerance=_GOAL_TOLERANCE,
                                            heading_tolerance=_HEADING_TOLERANCE if final
                                            else None,
                                            stop=stop if cancel is not None or gesture is not None
                                            else None, near_enough=near_enough)
        except NavigationError:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
        if attempt.reached:
            return MoveReport(True, self.pose(), attempt.travelled)
        if attempt.reason is StopReason.CANCELED and cancel is not None and cancel.cancelled:
            return MoveReport(False, self.pose(), attempt.travelled, Blocker.CANCELLED)
        if attempt.reason is StopReason.CANCELED and gesture is not None:
            self.events.record("robot.stopped", person=companion)
            return MoveReport(False, self.pose(), attempt.travelled, Blocker.STOPPED, None,
                              companion)
        person = self._person_in_the_way(target, avoid_doors)
        blocker = Blocker.PERSON if person is not None else Blocker.OBSTRUCTED
        self.events.record("robot.stuck", person=person or None)
        return MoveReport(False, self.pose(), attempt.travelled, blocker, None, person or None)

    def _record_replan(self, found: bool) -> None:
        self.events.record("robot.replan", found=found)

    def _door_blocker(self, door: str, *, from_afar: bool = False
                      ) -> tuple[Blocker, str | None] | None:
        """Is ``door`` shut, or does someone (or something) stand in it? None: the way
        through is clear. Standing before it, a door the robot cannot tell is open counts
        as shut; ``from_afar`` it may not tell, and only what stands in it counts."""
        state = self.door_is_open(door)
        if state is False or (state is None and not from_afar):
            return (Blocker.DOOR_CLOSED, None)
        # A leaf left half open, furniture beside the jamb or someone by the doorway keep
        # the robot out only when no straight way through the doorway is wide enough.
        if self._way_through(door) is not None:
            return None
        return (Blocker.PERSON, self._person_near(self.world.doors[door].position, 0.8) or None)

    def _pass_narrow_doorway(self, door: str, avoid_doors: frozenset[str]) -> float:
        """Standing before ``door`` (open, and a way through it seen): when its widest
        straight way leaves little room or runs slanted (past a leaf left half open, or
        furniture by a jamb), line up with that way and drive along it at a crawl, as
        stage 2's safety margin would not; metres driven. A roomy doorway is left to the
        next leg's ordinary drive."""
        way = self._way_through(door)
        if way is None or not way.narrow:
            return 0.0
        here = self.pose().xy()
        entry, exit_ = sorted((way.entry, way.exit), key=lambda end: math.dist(here, end))
        heading = math.atan2(exit_[1] - entry[1], exit_[0] - entry[0])
        self.events.record("robot.doorway", door=door, room=round(way.room, 3),
                           slant=round(way.slant, 3))
        start = self.body.odometry().pose
        if math.dist(here, entry) > _ON_THE_WAY:
            # a short straight step onto the way when it is free, else the ordinary drive
            self._turn_towards(entry)
            if not drive_straight(self.body, self.localise, here, entry):
                attempt = self.navigation.drive(Pose(*entry, heading), avoid_doors,
                                                tolerance=_ON_THE_WAY,
                                                heading_tolerance=_HEADING_TOLERANCE)
                if not attempt.reached:
                    return attempt.travelled
        self._turn_towards(exit_)
        drive_straight(self.body, self.localise, entry, exit_)
        return math.dist(start.xy(), self.body.odometry().pose.xy())

    def _way_through(self, door: str) -> WayThrough | None:
        """The widest straight way through ``door`` past what the laser sees now."""
        model = self.world.doors[door]
        normal = self.world.door_normal(door)
        # what the laser sees, and the furniture the map has (out of view round a jamb)
        near = ShapelyPoint(model.position).buffer(_FURNITURE_NEAR_DOOR)
        outlines = [np.asarray(placement.footprint.exterior.segmentize(_OUTLINE_STEP).coords)
                    for placement in self.world.placements.values()
                    if placement.model.kind is PlacementKind.FURNITURE
                    and placement.footprint.intersects(near)]
        points = np.concatenate([self._scan_on_map(), *outlines])
        return way_through(points, model.position, normal, model.width,
                           self.world.model.wall_thickness, self.body.radius)

    def _doorway_clears(self, door: str, avoid_doors: frozenset[str]) -> bool:
        """Someone standing in ``door`` may be passing through, or stepping out of it
        (asked to let the robot by, they may have to come the robot's way, and cannot
        while it stands before the doorway): step out of their way (``make_way``), and
        watch the doorway a few seconds; whether a way through opened. Asking again at
        once would only stop them where they stand."""
        navigation = self.navigation
        seen = navigation.memory.observe(self.body.now(), self.pose(), self.body.scan())
        navigation.make_way(self.pose(), seen, avoid_doors)
        self.body.command_velocity(Twist())
        for _ in range(round(_WATCH_DOORWAY / _WATCH_EVERY)):
            self.body.tick(max(1, round(_WATCH_EVERY / self.body.tick_period)))
            if self._way_through(door) is not None:
                return True
        return False

    def _door_ahead_blocked(self, legs: list[_Leg]
                            ) -> tuple[str, Blocker, str | None] | None:
        """The first door still to pass, within sight, that is shut or has something
        standing in it: (door, blocker, who if known)."""
        here = self.pose().xy()
        for leg in legs:
            if leg.door is None or math.dist(
                    here, self.world.doors[leg.door].position) > _SEES_THE_DOOR:
                continue
            blocked = self._door_blocker(leg.door, from_afar=True)
            if blocked is not None:
                return (leg.door, *blocked)
        return None

    def _person_in_the_way(self, target: Pose, avoid_doors: frozenset[str]) -> str | None:
        """Who stands on the way the robot would take if nobody were there (or, with no
        such way, nearest the robot), so that they can be asked to let it by: their
        name, "" for someone the robot cannot name, None for nobody."""
        here = self.pose()
        path = self.navigation.plan_wide(here, target, avoid_doors, np.zeros((0, 2)))
        if path is None:
            return self._person_near(here.xy(), 1.5)
        seen = [(_distance_to_path(p.position, path), p.name)
                for p in self.perceive_people()]
        blocking = sorted((gap, name or "") for gap, name in seen if gap <= _IN_THE_WAY)
        return blocking[0][1] if blocking else None

    def _turn_towards(self, point: tuple[float, float]) -> None:
        """Turn on the spot towards ``point`` and take a fresh sweep."""
        self.navigation.face(point)
        self.body.tick()

    def _person_near(self, point: tuple[float, float], reach: float) -> str | None:
        """The name of the person seen nearest ``point`` within ``reach``; "" when the
        robot cannot name them, None for nobody."""
        seen = [p for p in self.perceive_people() if math.dist(p.position, point) <= reach]
        seen.sort(key=lambda p: math.dist(p.position, point))
        return (seen[0].name or "") if seen else None

    def _seen_near(self, person: str, reach: float) -> list[PersonPercept]:
        """``person`` as a look shows them; when they are not named but someone nameless
        stands within ``reach`` (behind the robot, their face out of the head's turn), the
        robot turns to the nearest of them and looks again."""
        people = self.perceive_people()
        named = [p for p in people if p.name == person]
        here = self.pose()
        nameless = sorted((p for p in people if p.name is None and
                           math.dist(p.position, here.xy()) <= reach),
                          key=lambda p: math.dist(p.position, here.xy()))
        if named or not nameless:
            return named
        target = nameless[0].position
        self.move_to(Pose(here.x, here.y, math.atan2(target[1] - here.y, target[0] - here.x)))
        return [p for p in self.perceive_people() if p.name == person]

    def _scan_on_map(self) -> np.ndarray:
        """The latest scan's returns on the map, placed by the pose estimate."""
        return scan_on_map(self.pose(), self.body.scan())

    def _record_view(self) -> None:
        """Log what the robot saw and believed at the end of a motion, for the map picture."""
        laser = np.round(self._scan_on_map(), 3)
        particles = self.localisation.particles
        if len(particles) > _PARTICLES_SHOWN:
            particles = particles[:: math.ceil(len(particles) / _PARTICLES_SHOWN)]
        world = self.world.name
        self.events.record("robot.laser", world=world, points=laser.tolist())
        self.events.record("robot.particles", world=world,
                           points=np.round(particles, 3).tolist())

    def follow(self, person: str, goal: Pose | None, *,
               cancel: CancelToken | None = None) -> MoveReport:
        """Follow ``person`` by tracking them (``homebot.embodied.following``): asked to
        go ahead (to the room of ``goal`` when given), they lead; the robot keeps behind
        until they say stop, show it, or stand still where they were going."""
        seen = self._seen_near(person, _FOLLOWING_REACH)
        if not seen or math.dist(seen[0].position, self.pose().xy()) > _FOLLOWING_REACH:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
        room = self.world.room_at(*goal.xy()) if goal is not None else None
        if room is not None:
            self.say(f"{person}, please go ahead to the {room}, I will follow you.")
        else:
            self.say(f"{person}, please go ahead, I will follow you. Say stop when we are "
                     f"there.")
        answer = self.conversation.listen("yes_no")
        if answer.text is not None and answer.text.split()[0] in _NO:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH, None, person)
        result = self.following().follow(room, cancel=cancel, person_near=seen[0].position)
        pose = self.pose()
        if result.end is FollowEnd.CANCELLED:
            return MoveReport(False, pose, result.travelled, Blocker.CANCELLED)
        if result.end in (FollowEnd.STOP_SAID, FollowEnd.STOP_SHOWN, FollowEnd.ARRIVED):
            if result.last_seen is not None and \
                    self.world.room_at(*result.last_seen) != self.world.room_at(*pose.xy()):
                # stopped behind them across a doorway: come into their room, up to them
                self._come_up_to(result.last_seen)
            return MoveReport(True, self.pose(), result.travelled)
        return MoveReport(False, pose, result.travelled, Blocker.NO_PATH, None, person)

    def _come_up_to(self, person: tuple[float, float]) -> None:
        """Drive along the way to ``person`` until ``_ASKING_DISTANCE`` short of them (or
        nearer, to be in their room), facing them."""
        plan = self.navigator.plan(self.pose().xy(), person)
        if plan is None:
            return
        points = [(float(x), float(y)) for x, y in plan.waypoints]
        room = self.world.room_at(*person)
        spots = [way[-1] for short in _COMING_UP if (way := shortened(points, short))]
        spot = next((spot for spot in spots if self.world.room_at(*spot) == room), None)
        if spot is not None:
            self.move_to(Pose(spot[0], spot[1], math.atan2(person[1] - spot[1],
                                                           person[0] - spot[0])))

    def following(self, parameters: FollowParameters | None = None) -> Following:
        """A follower of one person with this robot's laser, map, ears and eyes."""
        conversation = self.conversation
        conversation.start_overhearing()
        people_look = self.people_look
        return Following(
            self.body, self.world, self.navigator, self.controller, self.localise,
            people_look.off_the_map if people_look is not None else _everywhere,
            self.navigation.memory.unexpected, self.events,
            heard_stop=lambda: _says_stop(conversation.overheard(STOP)),
            stop_shown=_shows_stop,
            clothes=people_look.clothes_at if people_look is not None else None,
            ask_way=conversation.say, parameters=parameters)

    # ------------------------------------------------------------ perception and hands

    def perceive_objects(self, placement: str) -> list[Detection]:
        """What the head camera sees on ``placement`` (nothing without a camera look)."""
        if self.looking is None:
            return []
        return self.looking.look(placement, self.pose())

    def perceive_people(self) -> list[PersonPercept]:
        """Who the laser and the head camera see (nobody without a people look)."""
        if self.people_look is None:
            return []
        return self.people_look.look()

    # A body without an arm (``ArmedBodyRobot`` has one) holds nothing and takes nothing.

    def grasp(self, detection: Detection, hand: str) -> str | None:
        return f"I have no arm to take the {detection.label} with"

    def held(self, hand: str) -> Detection | None:
        return None

    def release(self, hand: str, placement: str) -> None:
        return None

    def hand_over(self, hand: str, person: str) -> bool:
        return False

    def receive(self, hand: str, person: str) -> Detection | None:
        return None

    def open_door(self, door: str) -> bool:
        """Whether ``door`` is open, as the laser sees it from before it. The arm does not
        open doors inside a task yet: a shut door stays shut (the executive's door
        protocol then asks someone to open it)."""
        return self.door_is_open(door) is True

    def door_is_open(self, door: str) -> bool | None:
        model = self.world.doors.get(door)
        here = self.pose()
        if model is None or math.dist(here.xy(), model.position) > _SEES_THE_DOOR:
            return None
        normal = self.world.door_normal(door)
        self.body.tick()  # a fresh sweep: the door may have moved since the last one
        seen = door_seen_open(self.body.scan(), self.pose(), model.position, normal,
                              model.width)
        if seen is None:
            # The doorway is behind the robot or at the edge of its view: turn to face it
            # and look again, rather than take a door it cannot see for shut.
            self._turn_towards(model.position)
            seen = door_seen_open(self.body.scan(), self.pose(), model.position, normal,
                                  model.width)
        if seen is False and self._person_near(model.position, model.width / 2) is not None:
            return True  # the laser cannot tell a leaf from someone filling the doorway
        if seen is True and self._way_through(door) is None and leaf_barely_ajar(
                self._scan_on_map(), model.position, normal, model.width, self.body.radius) \
                and self._person_near(model.position, model.width) is None:
            # A leaf left barely ajar: the beams pass its gap, the robot cannot. It is to be
            # opened, as a shut door is; nobody stands there to step aside.
            return False
        return seen

    def say(self, text: str) -> None:
        """Speak ``text`` through the body's speaker (espeak-ng, the ``speech`` extra): the
        body's clock runs for as long as it sounds. A body without a speaker says nothing
        (the log keeps what it would have said)."""
        self.conversation.say(text)

    def ask(self, person: str, question: str) -> str | None:
        """Ask ``person`` aloud (by name) and hear their answer in the microphone, in the
        dialogue state the question calls for; None when nobody answers, twice, or the
        answer is off the point, twice."""
        from homebot.speech.answers import answer_state

        spoken = f"{person}, {question}" if person else question
        return self.conversation.ask(spoken, answer_state(question))

    # ------------------------------------------------------------ faces

    def introduce(self, utterance: str) -> str | None:
        """Hear ``utterance`` from the person in front: when it gives their name ("my name
        is Maria"), their face is enrolled from the head camera's views under it, to be
        recognised afterwards (``face_in_front``). The name enrolled, or None (no name
        given, nobody in front, or no face seen)."""
        if self.acquaintances is None:
            return None
        name = self.acquaintances.introduce(utterance, self.face_views(_INTRODUCTION_VIEWS))
        if name is not None:
            self.events.record("robot.met", person=name)
        return name

    def face_in_front(self) -> str | None:
        """The name of the person in front, recognised by face among the people met;
        None for nobody in front, a stranger, or no faces seen."""
        if self.acquaintances is None:
            return None
        return self.acquaintances.recognise(self.face_views(_RECOGNITION_VIEWS))

    def face_views(self, views: int) -> list[np.ndarray]:
        """The head camera's close-ups of the face in front (``Body.face_crops``); none
        from a body without a face tracker."""
        try:
            return self.body.face_crops(views)
        except PartMissing:
            return []

    def request(self, person: str, request: HelpRequest, target: str) -> bool:
        """The request was just made aloud: listen for the yes. Asked to let the robot by
        from across a room, the robot first comes near and asks again."""
        if request is HelpRequest.STEP_ASIDE and self._come_near(person, target):
            self.say(f"Excuse me{f', {person}' if person else ''}, could you please let me "
                     "through?")
        return self.conversation.agreed()

    def _come_near(self, person: str, door: str) -> bool:
        """Come up to ``person`` (unnamed, or not known by face from here: whoever the
        robot cannot name and sees nearest the ``door``, or itself) before asking them to
        let the robot by, as far as the way allows: stopped by someone in a doorway across
        the room, the robot would otherwise ask from where they cannot hear it. Whether
        it moved."""
        here = self.pose()
        where = self.world.doors[door].position if door in self.world.doors else here.xy()
        people = self.perceive_people()
        # someone too far to know by face may be the one meant
        named = [p for p in people if person and p.name == person]
        seen = sorted(named or [p for p in people if p.name is None],
                      key=lambda p: math.dist(p.position, where))
        if not seen or math.dist(seen[0].position, here.xy()) <= _ASKING_DISTANCE + 0.3:
            return False
        plan = self.navigator.plan(here.xy(), seen[0].position)
        if plan is None or len(plan.waypoints) < 2:
            return False
        way = LineString(plan.waypoints)
        spot = way.interpolate(max(way.length - _ASKING_DISTANCE, 0.0))
        self.move_to(Pose(spot.x, spot.y, math.atan2(seen[0].position[1] - spot.y,
                                                     seen[0].position[0] - spot.x)))
        return True


def _distance_to_path(point: tuple[float, float],
                      path: tuple[tuple[float, float], ...]) -> float:
    """Metres from ``point`` to the nearest segment of ``path``."""
    if len(path) == 1:
        return math.dist(point, path[0])
    return float(LineString(path).distance(ShapelyPoint(point)))


#: answer recognisers by the names and objects they were built for (each takes seconds)
_RECOGNISERS: dict[tuple[tuple[str, ...], tuple[tuple[str, str], ...]], AnswerRecognizer] = {}


def _answer_recogniser(world: World) -> AnswerRecognizer:
    """The answer recogniser for ``world``'s names and drinks, built once per process."""
    from homebot.speech.answers import AnswerRecognizer

    key = (tuple(sorted(world.people)),
           tuple(sorted((name, obj.category) for name, obj in world.objects.items())))
    if key not in _RECOGNISERS:
        _RECOGNISERS[key] = AnswerRecognizer(world)
    return _RECOGNISERS[key]


def _shows_stop(frames: list[RgbdFrame], poses: list[Pose],
                person: tuple[float, float]) -> bool:
    """Whether the person at ``person`` shows the stop gesture in the burst ``frames``."""
    return gesture_from_depth(frames, poses, person) == "stop"


def _says_stop(heard: Hearing | None) -> bool:
    """Whether someone said stop: heard in the stop state, or the word itself in both
    decoders' hypotheses (a short "stop here." the two decoders word differently)."""
    if heard is None:
        return False
    if heard.text is not None:
        return True
    if heard.reason != "disagree":  # the grammar's search did not reach a whole sentence
        return False
    words = {word for hypothesis in heard.ngram_hypotheses[:3] for word in hypothesis.split()}
    said = set((heard.grammar_hypothesis or "").split())
    return bool(_STOP_WORDS & said & words)


def _everywhere(legs: np.ndarray) -> np.ndarray:
    """Every leg counts (no map to tell furniture's legs from people's)."""
    return np.ones(len(legs), dtype=bool)
