"""``ArmedBodyRobot``: the embodied robot whose grasps and releases run its arm in physics.

Shut doors are opened with the arm (``homebot.embodied.door_opening``). A grasp plans a
grasp and an arm motion (``homebot.manipulation``), moves the arm, closes
the gripper and lifts; whether the object is then in the hand is what the gripper and the
wrist sense, and what the simulator's physics made of the grasp, never a die. An object
more than 0.95 m away, or out of reach from where the robot stands, is reached after a step
beside the surface where it is nearest the object (not against a wall or other furniture;
two sides at most), and after a step the robot looks again: the step moved its pose
estimate's error under what it saw. A release puts the object on a free spot of the
placement (or drops it into a bin). The arm plans among the objects where the robot's
camera last saw them (``perceive_objects``; a picked object leaves that memory, a placed
one is where it was put: ``SeenObjects``, the arm's ``locate``); nothing else stands in
for an object it has not seen.
The robot has one arm: the world's second hand name is kept for the skills, but a grasp
with the gripper full is refused (the hand stays empty).
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
from shapely.geometry import LineString, Point

from homebot.embodied.door_opening import DoorOpening
from homebot.embodied.robot import BodyRobot
from homebot.geometry import Pose
from homebot.manipulation.control import ArmControl, PlaceOutcome
from homebot.manipulation.pick import PickOutcome, PickResult
from homebot.robot import Detection
from homebot.world import World, surface_height

__all__ = ["ArmedBodyRobot", "SeenObjects"]

_STAND_OFF = 0.4  #: metres from a surface's edge where the robot stands to reach over it
_STANDS_TRIED = 2  #: sides of the surface the robot steps to before it gives up
_COMFORTABLE_REACH = 0.95  #: metres from the base's centre to an object the arm grasps well
_STAND_STEP = 0.05  #: metres between the spots along a side that are tried
_ANOTHER_STAND = 0.3  #: metres from here for a stand to be another after failed grasps
#: why the arm did not even close the hand, as the robot says it
_NOT_TRIED = {
    PickOutcome.UNREACHABLE: "I cannot reach the {} from where I can stand",
    PickOutcome.NO_PATH: "my arm finds no free way to the {}",
    PickOutcome.TOO_HEAVY: "the {} is too heavy for my arm",
    PickOutcome.TRIED_ALL: "I tried every grasp of the {} I could find, and it kept slipping",
}
#: what the arm may do better from another spot beside the surface
_STEP_ASIDE = (PickOutcome.UNREACHABLE, PickOutcome.TRIED_ALL)
_BIN_CATEGORIES = ("bin", "trash", "trash can", "waste bin")
_PULL = 3.0  #: newtons more at the wrist than when held out: the person pulls
_PUT_IN = 0.8  #: newtons of change at the wrist: something was pushed into the palm
_FELT = 0.15  #: seconds a force must last to count (not a bump)
#: metres from where the robot looks at a shut door beyond which it drives up to it first
_WALK_UP = 0.35
_WAIT_FOR_TAKER = 8.0  #: seconds the robot holds an object out before keeping it
_WAIT_FOR_GIVER = 6.0  #: seconds the robot holds its open hand out before closing it


class SeenObjects:
    """Where the robot's camera last saw each object: the arm's ``Locate``. The arm's
    planning scene holds only what was seen; an object never seen is in no scene.

    Args:
        world: the map (surfaces and their heights).
    """

    def __init__(self, world: World) -> None:
        self.world = world
        #: where perception last saw each object: (placement, map position, heading or
        #: None); the ``ArmedBodyRobot`` keeps it
        self.places: dict[str, tuple[str, tuple[float, float], float | None]] = {}

    def __call__(self, name: str) -> tuple[float, float, float, float] | None:
        """Where the arm's planning scene puts ``name``: where perception last saw it, on
        the surface it was seen on at the map's height for it, turned as perception fitted
        it (0 when it did not); None for what it has not seen."""
        remembered = self.places.get(name)
        if remembered is None or remembered[0] not in self.world.placements:
            return None
        placement, (x, y), heading = remembered
        return (x, y, heading or 0.0, surface_height(self.world.placements[placement].model))


class ArmedBodyRobot(BodyRobot):
    """A ``BodyRobot`` that grasps, holds and releases with its arm.

    Args:
        *args: as ``BodyRobot``.
        arm: picking and placing over the same body, locating objects by ``seen``.
        seen: the memory of where objects were seen, which this robot keeps.
        doors: opens shut doors with the arm (None: the robot asks someone to).
        **kwargs: as ``BodyRobot``.

    Raises:
        ValueError: the arm locates objects some other way than by ``seen``.
    """

    def __init__(self, *args: Any, arm: ArmControl, seen: SeenObjects,
                 doors: DoorOpening | None = None, **kwargs: Any) -> None:
        if arm.locate is not seen:
            raise ValueError("the arm must locate objects by the robot's SeenObjects: "
                             "build it with ArmControl(body, world, seen)")
        super().__init__(*args, **kwargs)
        self.arm = arm
        self._holding: dict[str, Detection] = {}
        self._asked_for: str | None = None  #: the object last asked to be put in the hand
        self._handles = 0  #: the robot's own handles for what it was handed
        #: where perception last saw each object: (placement, map position, heading)
        self.seen = seen.places
        self.doors = doors
        #: doors the arm failed to open: not tried again (someone is asked instead)
        self._doors_failed: set[str] = set()

    def open_door(self, door: str) -> bool:
        """Open a shut ``door`` the robot stands before with the arm (Cosero §4.2:
        ``homebot.embodied.door_opening``) when the hand is free; whether it is open is
        then what the laser sees. An attempt that fails leaves the door to whoever the
        robot asks; the arm does not try that door again."""
        seen = self.door_is_open(door)
        if seen is True:
            return True
        if seen is None or self.doors is None or self._holding or \
                self.arm.holding is not None or door in self._doors_failed:
            return False
        # Up to the door first, on this side of it, by navigation: a door seen shut from
        # afar (the way's start) is no door to reach for from there.
        before = self.doors.looking_pose(door, self.pose())
        if math.dist(self.pose().xy(), before.xy()) > _WALK_UP:
            self.move_to(before, frozenset({door}))
            self.localise()
        attempt = self.doors.open(door, self.pose())
        self.localise()
        opened = self.door_is_open(door) is True
        if not opened:
            self._doors_failed.add(door)
        self.events.record("robot.open_door", door=door, opened=opened,
                           reason=attempt.reason, seconds=round(attempt.seconds, 2),
                           degrees=round(attempt.believed_degrees, 1))
        return opened

    def perceive_objects(self, placement: str) -> list[Detection]:
        detections = super().perceive_objects(placement)
        for name in [n for n, (where, _, _) in self.seen.items() if where == placement]:
            del self.seen[name]  # not there any more, or seen anew below
        for detection in detections:
            if detection.position is not None:
                self.seen[detection.label] = (placement, detection.position, detection.heading)
        return detections

    def grasp(self, detection: Detection, hand: str) -> str | None:
        if hand in self._holding:
            return None
        here = self.pose()
        far = detection.position is not None and math.dist(
            (here.x, here.y), detection.position) > _COMFORTABLE_REACH
        if self.arm.tried_out(detection.label):  # nothing new to try: no step, no reach
            result = PickResult(PickOutcome.TRIED_ALL, detail="given up")
            self.events.record("robot.pick", object=detection.label,
                               outcome=result.outcome.value, detail=result.detail, planning=0.0)
            return _NOT_TRIED[result.outcome].format(detection.label)
        # At the edge of its reach the arm grasps at full stretch, and a grasp off by a
        # centimetre slips: the robot first steps nearer. Out of reach from here, too, it
        # steps to the sides of the surface nearest the object, and so it does when every
        # grasp found from here failed before: from another side it sees the object anew
        # (what hid part of it may not) and reaches it another way.
        result = PickResult(PickOutcome.UNREACHABLE, detail="too far to grasp well") if far \
            else self.arm.pick(detection.label, here, detection.position, detection.mass)
        where = detection.position or self.arm.locate(detection.label)
        stands = iter([stand for stand in self._stands_before(where[:2])
                       if result.outcome is PickOutcome.UNREACHABLE or
                       math.dist(stand.xy(), here.xy()) > _ANOTHER_STAND]
                      if where is not None and result.outcome in _STEP_ASIDE else [])
        if far:  # from here, too, if no step brings it nearer
            stands = itertools.chain(stands, (here,))
        for stand in itertools.islice(stands, _STANDS_TRIED):
            if not self.move_to(stand).reached:
                continue
            detection = self._look_again(detection)
            result = self.arm.pick(detection.label, self.pose(), detection.position,
                                   detection.mass)
            if result.outcome not in _STEP_ASIDE:
                break
        self.events.record("robot.pick", object=detection.label, outcome=result.outcome.value,
                           detail=result.detail,
                           planning=round(result.planning_seconds, 4))
        if result:
            self._holding[hand] = detection
            self.seen.pop(detection.label, None)  # in the hand now, not on the surface
        return _NOT_TRIED.get(result.outcome, "").format(detection.label) or None

    def _look_again(self, detection: Detection) -> Detection:
        """The object as seen from where the robot now stands (the step moved the pose
        estimate's error: what was seen from before is off by that much): the detection of
        the same object nearest where it was seen; the old one if it is not seen now."""
        seen = self.seen.get(detection.label)
        if seen is None or detection.position is None:
            return detection
        before = detection.position
        again = [d for d in self.perceive_objects(seen[0])
                 if d.label == detection.label and d.position is not None]
        if not again:
            return detection
        return min(again, key=lambda d: math.dist(before, d.position or before))

    def held(self, hand: str) -> Detection | None:
        detection = self._holding.get(hand)
        if detection is not None and not self.arm.gripper_holds():
            self.arm.holding = None  # it slipped out: the fingers closed on nothing
            del self._holding[hand]
            return None
        return detection

    def release(self, hand: str, placement: str) -> None:
        if self._holding.pop(hand, None) is None:
            return
        known = self.world.placements.get(placement)
        done = False
        if known is not None:
            drop = known.model.category.lower() in _BIN_CATEGORIES
            held = self.arm.holding.name if self.arm.holding is not None else None
            outcome = self._put_down(placement, drop)
            # No free spot within reach from where navigation left it: the robot steps
            # beside the surface, nearest side first, as it does to grasp.
            centre = known.model.center
            stands = [] if outcome.done else self._stands_before(
                (float(centre[0]), float(centre[1])))
            for stand in stands[:_STANDS_TRIED]:
                if self.move_to(stand).reached:
                    outcome = self._put_down(placement, drop)
                    if outcome.done:
                        break
            if held is not None and outcome.done and outcome.spot is not None:
                self.seen[held] = (placement, outcome.spot, None)  # where it was put
            self.events.record("robot.place", placement=placement, done=outcome.done,
                               detail=outcome.detail)
            done = outcome.done
        if not done:  # no spot: let go where the hand is; what happens is physics'
            self.body.gripper().command(0.2)
            self.body.tick(max(1, round(0.5 / self.body.tick_period)))
            self.arm.holding = None

    def _put_down(self, placement: str, drop: bool) -> PlaceOutcome:
        """Look at the placement first (what stands there now is in the arm's scene, so
        the free spot is free), then put what the hand holds on it."""
        if not drop:
            self.perceive_objects(placement)
        return self.arm.place(placement, self.pose(), drop=drop)

    def receive(self, hand: str, person: str) -> Detection | None:
        """Hold the open hand out (the person was asked to put the object in); once the
        wrist feels something pushed into the palm, or after a while, close; whether the
        robot then holds something is what its fingers sense (Cosero §7.3.1)."""
        if hand in self._holding or self.arm.holding is not None:
            return None
        self._face(person)
        self.arm.offer_hand(self.pose())
        wanted = self._asked_for or "object"
        felt = self._wait_for_wrench(_PUT_IN, _WAIT_FOR_GIVER)
        if not self.arm.close_on_handed(wanted, self.pose()):
            self.events.record("robot.receive", person=person, held=False, felt=felt)
            self.arm.tuck(self.pose())
            return None
        received = Detection(wanted, self.world.objects[wanted].category if wanted in
                             self.world.objects else "", self._next_handle())
        self.events.record("robot.receive", person=person, held=True, object=wanted,
                           felt=felt)
        self._holding[hand] = received
        return received

    def hand_over(self, hand: str, person: str) -> bool:
        """Hold the object out to ``person``, compliant; let go once the wrist feels them
        pull (Cosero §7.3.1), and never before; a person who does not pull within a while
        leaves it in the hand. Whether it is gone is what the fingers sense."""
        if hand not in self._holding or self.arm.holding is None:
            return False
        self._face(person)
        self.arm.hold_out(self.pose())
        # A pull is felt across the wrist, towards the person: what slips out of the
        # fingers changes the wrist's load too, but downwards.
        pulled = self._wait_for_wrench(_PULL, _WAIT_FOR_TAKER,
                                       sensor_to_map=self.arm.hand_orientation(self.pose()))
        if not pulled or not self.arm.gripper_holds():
            # not taken, or it slipped out of the hand (fingers shut on nothing): not given
            self.events.record("robot.hand_over", person=person, released=False,
                               slipped=pulled)
            if pulled:
                self.arm.holding = None
                del self._holding[hand]
            self.arm.tuck(self.pose())
            return False
        self.arm.let_go()
        del self._holding[hand]
        self.events.record("robot.hand_over", person=person, released=True)
        self.arm.tuck(self.pose())
        return True

    def say(self, text: str) -> None:
        # what the robot asks for, it expects in its hand ("please put the cup in my hand")
        if "in my hand" in text:
            named = [name for name in self.world.objects if name in text.lower()]
            self._asked_for = max(named, key=len) if named else None
        super().say(text)

    def _wait_for_wrench(self, threshold: float, seconds: float, *,
                         sensor_to_map: np.ndarray | None = None) -> bool:
        """Tick until the wrist's force differs from what it was by more than ``threshold``
        newtons for ``_FELT`` seconds; False after ``seconds`` without. Given the sensor's
        orientation on the map, only the horizontal part of the change counts."""
        start = self.body.wrist_wrench().force
        step = max(1, round(0.05 / self.body.tick_period))
        waited = held = 0.0
        while waited < seconds:
            self.body.tick(step)
            waited += step * self.body.tick_period
            difference = self.body.wrist_wrench().force - start
            if sensor_to_map is not None:
                difference = (sensor_to_map @ difference)[:2]
            change = float(np.linalg.norm(difference))
            held = held + step * self.body.tick_period if change > threshold else 0.0
            if held >= _FELT:
                return True
        return False

    def _face(self, person: str) -> None:
        """Turn to where ``person`` is seen, to hold the hand out to them."""
        seen = [p for p in self.perceive_people() if p.name == person]
        if not seen:
            return
        here = self.pose()
        x, y = seen[0].position
        self.move_to(Pose(here.x, here.y, math.atan2(y - here.y, x - here.x)))

    def _next_handle(self) -> int:
        self._handles += 1
        return -self._handles

    def _stands_before(self, point: tuple[float, float]) -> list[Pose]:
        """Poses beside the surface under ``point``, facing it, nearest to it first.

        At most one per side of the surface: the free spot just off the side nearest
        ``point``, in the surface's room (a side against a wall or other furniture may
        offer none).
        """
        seen = Point(point)
        found = [(p.footprint.distance(seen), p) for p in self.world.placements.values()
                 if p.footprint.covers(seen)]
        if not found:
            return []
        surface = min(found, key=lambda pair: pair[0])[1]
        ring = surface.footprint.exterior
        turn = 1.0 if ring.is_ccw else -1.0  # the outward normal is right of a ccw ring
        stands: list[tuple[float, Pose]] = []
        for start, end in itertools.pairwise(ring.coords):
            side = LineString((start, end))
            nx, ny = turn * (end[1] - start[1]) / side.length, turn * (start[0] - end[0]) / \
                side.length
            spots = []
            for along in np.append(np.arange(0.0, side.length, _STAND_STEP), side.length):
                edge = side.interpolate(float(along))
                x, y = edge.x + nx * _STAND_OFF, edge.y + ny * _STAND_OFF
                # in the surface's own room: beyond the wall a surface stands against the
                # robot would look at the wall (the kitchen cabinet from the corridor)
                if self.world.footprint_problem(x, y) is None and \
                        self.world.room_at(x, y) == surface.room:
                    spots.append((math.dist((x, y), point), x, y))
            if spots:
                distance, x, y = min(spots)
                stands.append((distance, Pose(x, y, math.atan2(point[1] - y, point[0] - x))))
        return [pose for _, pose in sorted(stands, key=lambda pair: pair[0])]
