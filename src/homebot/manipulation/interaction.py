"""Physical human-robot interaction on a compliant arm (Cosero §7.3, §4.2).

Each behaviour is a small state machine run once per control tick: it reads the arm
(``ArmReading``: joints, hand pose, Jacobian) and, where it needs them, the wrist's
force-torque sensor and the table's pitch, and returns a ``Command``: where the hand
should be and how compliant (for ``ComplianceController``), whether the gripper is
closed, how the base should move (a ``Twist`` in the base frame) and the torso's height.
None of them reads the simulator; the person's intention reaches them only through the
arm's displacement and the wrist.

- ``Handover``: compliant forward, upward and in pitch; lets go when the hand is pulled
  far enough that the pull must exceed the threshold, and never for less.
- ``Receive``: offers the open hand, closes when an object is pushed into it (the palm
  feels it at the wrist), and has it when the person lets go (the wrist feels its weight).
- ``GuidedByHand``: compliant in the plane; the base drives to bring the hand back to its
  place in front of the robot and turns towards where it is led.
- ``CarryTable``: holds one end of a table, waits until the person lifts theirs
  (pitch 0.02 rad), then keeps the table level while following in the plane, and
  lowers when the person does.
- ``DoorMotion``: holds a door's handle compliant in the plane and in yaw and moves it
  round where it believes the hinge is, from where the hand actually is each tick, so
  the door's true circle prevails; opens, then closes it against its frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum

import numpy as np

from homebot.geometry import wrap_angle, yaw_rotation
from homebot.manipulation.compliance import AxisCompliance, Compliance
from homebot.robot.body import Twist

__all__ = [
    "CarryPhase",
    "CarryTable",
    "Command",
    "DoorMotion",
    "DoorPhase",
    "GuidedByHand",
    "Handover",
    "Receive",
    "ReceivePhase",
    "to_base",
    "to_odometry",
]


@dataclass(frozen=True)
class Command:
    """What a behaviour wants this tick."""

    hand_position: np.ndarray  #: base frame
    hand_rotation: np.ndarray  #: base frame, 3 × 3
    compliance: Compliance
    gripper_closed: bool
    base: Twist = field(default_factory=Twist)
    torso: float | None = None  #: metres; None: stay


def _soft(span: float, min_force: float, max_force: float, damping: float,
          stiffness: float = 1500.0) -> AxisCompliance:
    return AxisCompliance(stiffness=stiffness, damping=damping, max_force=max_force,
                          min_force=min_force, span=span)


class Handover:
    """Hold an object out and release it when the person pulls (Cosero §7.3.1).

    The hand is compliant forward (+x), upward (+z) and in pitch. A steady pull ``F``
    moves it ``span·(F − min_force)/(max_force − min_force)`` along each compliant axis;
    the behaviour reads the pull back from that displacement and lets go once the pull
    read exceeds ``release_force`` for ``confirm`` ticks in a row. ``release_force`` sits
    between the largest bump the person may give by accident and the pull threshold.
    """

    def __init__(self, hand_position: np.ndarray, hand_rotation: np.ndarray, *,
                 threshold: float = 10.0, release_fraction: float = 0.75,
                 confirm: int = 2) -> None:
        self.target = np.asarray(hand_position, dtype=float)
        self.rotation = np.asarray(hand_rotation, dtype=float)
        self.threshold = threshold
        self.release_force = release_fraction * threshold
        self.confirm = confirm
        forward = _soft(0.15, 2.0, 40.0, damping=40.0)
        pitch = _soft(0.4, 0.2, 8.0, damping=3.0, stiffness=40.0)
        self.compliance = Compliance().with_axes(
            x=AxisCompliance(**{**forward.__dict__, "positive": True}),
            z=AxisCompliance(**{**forward.__dict__, "positive": True}),
            pitch=AxisCompliance(**{**pitch.__dict__, "positive": True, "negative": True}))
        self.released_at: float | None = None
        self._over = 0
        self.pull_read = 0.0

    def felt_pull(self, shift: np.ndarray) -> float:
        """The pull (N) that would hold the hand where it is, read from the forward and
        upward displacement."""
        total = 0.0
        for index in (0, 2):
            axis = self.compliance.axes[index]
            d = float(shift[index])
            if d <= 0:
                continue
            force = axis.min_force + min(1.0, d / axis.span) * (axis.max_force - axis.min_force)
            total += force * force
        return math.sqrt(total)

    def update(self, now: float, shift: np.ndarray) -> Command:
        """``shift``: the hand's displacement from its target (``ComplianceController.shift``)."""
        if self.released_at is None:
            self.pull_read = self.felt_pull(shift)
            self._over = self._over + 1 if self.pull_read >= self.release_force else 0
            if self._over >= self.confirm:
                self.released_at = now
        return Command(self.target, self.rotation, self.compliance,
                       gripper_closed=self.released_at is None)


class ReceivePhase(StrEnum):
    """Where a ``Receive`` is."""

    OFFERING = "offering"  #: open hand held out, waiting for an object
    CLOSING = "closing"  #: something touched the palm; the fingers close
    HOLDING = "holding"  #: the person let go; the robot carries the weight
    EMPTY = "empty"  #: the fingers closed on nothing


class Receive:
    """Take an object a person puts into the open hand (Cosero §7.3.1, the other way).

    Cosero senses the object between its fingers with in-hand distance sensors; this
    arm has none, so the palm's touch is felt at the wrist: the object pushed into the
    hand presses back along the hand's axis (``touch`` newtons above the resting
    reading). Then the fingers close; once they have closed (``close_time``), the robot
    holds if the fingers stopped apart (something is between them) and the wrist feels
    the object's weight after the person lets go.
    """

    def __init__(self, hand_position: np.ndarray, hand_rotation: np.ndarray, *,
                 touch: float = 1.5, close_time: float = 0.6, min_width: float = 0.01,
                 min_weight: float = 1.0) -> None:
        self.target = np.asarray(hand_position, dtype=float)
        self.rotation = np.asarray(hand_rotation, dtype=float)
        self.touch, self.close_time = touch, close_time
        self.min_width, self.min_weight = min_width, min_weight
        self.compliance = Compliance()
        self.phase = ReceivePhase.OFFERING
        self.rest: np.ndarray | None = None  #: the wrist's reading with the hand empty
        self.closed_at: float | None = None
        self.weight = 0.0

    def update(self, now: float, wrist_force: np.ndarray, gripper_width: float) -> Command:
        """``wrist_force``: the sensor's force (its frame, x along the hand)."""
        force = np.asarray(wrist_force, dtype=float)
        if self.rest is None:
            self.rest = force.copy()
        change = force - self.rest
        if self.phase is ReceivePhase.OFFERING and float(np.linalg.norm(change)) > self.touch:
            self.phase, self.closed_at = ReceivePhase.CLOSING, now
        elif self.phase is ReceivePhase.CLOSING and self.closed_at is not None and \
                now - self.closed_at >= self.close_time:
            self.weight = float(np.linalg.norm(change))
            if gripper_width < self.min_width:
                self.phase = ReceivePhase.EMPTY
            elif self.weight >= self.min_weight:
                self.phase = ReceivePhase.HOLDING
        return Command(self.target, self.rotation, self.compliance,
                       gripper_closed=self.phase is not ReceivePhase.OFFERING)


class GuidedByHand:
    """Follow the hand a person leads (Cosero §7.3.2).

    The hand is compliant in x and y. How far it is pulled sets the base's speed
    (``gain`` per second on the displacement, capped at ``speed``; below ``dead_band``, a
    light touch, the base stays). Where the base goes: given the base's odometry, it
    keeps a trail of where its hand has been and drives along that trail (pure pursuit,
    ``lookahead`` metres ahead), turning to keep the hand straight ahead; so the base
    walks in the person's footsteps instead of cutting corners behind its hand. Without
    odometry it drives along the displacement itself.
    """

    def __init__(self, hand_position: np.ndarray, hand_rotation: np.ndarray, *,
                 gain: float = 6.0, speed: float = 0.7, turn_gain: float = 2.0,
                 dead_band: float = 0.005, lookahead: float = 0.3) -> None:
        self.target = np.asarray(hand_position, dtype=float)
        self.rotation = np.asarray(hand_rotation, dtype=float)
        self.gain, self.speed, self.turn_gain, self.dead_band = gain, speed, turn_gain, dead_band
        self.lookahead = lookahead
        planar = _soft(0.2, 3.0, 50.0, damping=40.0)
        both = {"positive": True, "negative": True}
        self.compliance = Compliance().with_axes(
            x=AxisCompliance(**{**planar.__dict__, **both}),
            y=AxisCompliance(**{**planar.__dict__, **both}))
        self.led = False
        self.trail: list[np.ndarray] = []  #: where the hand has been (odometry frame)

    def update(self, shift: np.ndarray, pose: tuple[float, float, float] | None = None
               ) -> Command:
        """``shift``: the hand's displacement; ``pose``: the base's odometry (x, y, yaw)."""
        dx, dy = float(shift[0]), float(shift[1])
        pull = math.hypot(dx, dy)
        hand = self.target[:2] + np.array([dx, dy])
        if pose is not None:
            c, s = math.cos(pose[2]), math.sin(pose[2])
            here = np.array(pose[:2])
            crumb = here + np.array([c * hand[0] - s * hand[1], s * hand[0] + c * hand[1]])
            if not self.trail:  # the way from the base to the hand, to start on
                steps = max(1, int(math.dist(here, crumb) / 0.02))
                self.trail.extend(here + (crumb - here) * k / steps for k in range(steps))
            if math.dist(crumb, self.trail[-1]) > 0.02:
                self.trail.append(crumb)
        twist = Twist()
        if pull > self.dead_band:
            self.led = True
            direction = np.array([dx, dy]) / pull
            ahead = pull
            turning = True
            if pose is not None:
                along = self._along_trail(np.array(pose[:2]), pose[2])
                ahead = float(np.dot(along, [dx, dy]))
                if ahead > self.dead_band:  # led onwards: in the hand's footsteps
                    direction = along
                else:  # pushed back: give way straight back, off no trail, not turning
                    direction = np.array([-1.0, 0.0]) if dx < 0 else np.zeros(2)
                    ahead, turning = abs(dx), False
            speed = max(0.0, min(self.speed, self.gain * (ahead - self.dead_band)))
            wz = self.turn_gain * math.atan2(hand[1], hand[0]) if turning else 0.0
            twist = Twist(speed * float(direction[0]), speed * float(direction[1]),
                          max(-1.0, min(1.0, wz)))
        return Command(self.target, self.rotation, self.compliance, gripper_closed=True,
                       base=twist)

    def _along_trail(self, here: np.ndarray, yaw: float) -> np.ndarray:
        """The unit direction (base frame) to the trail point ``lookahead`` past the
        trail's point nearest the base."""
        trail = np.asarray(self.trail)
        nearest = int(np.argmin(np.linalg.norm(trail - here, axis=1)))
        goal = trail[-1]
        for point in trail[nearest + 1:]:
            if math.dist(point, here) >= self.lookahead:
                goal = point
                break
        world = goal - here
        norm = float(np.linalg.norm(world))
        if norm < 1e-6:
            return np.zeros(2)
        c, s = math.cos(yaw), math.sin(yaw)
        return np.array([c * world[0] + s * world[1], -s * world[0] + c * world[1]]) / norm


class CarryPhase(StrEnum):
    """Where a ``CarryTable`` is."""

    WAITING = "waiting"  #: holding the table on the floor until the person lifts
    CARRYING = "carrying"  #: lifted: level and following
    LOWERING = "lowering"  #: the person put their end down: the robot lowers too
    DONE = "done"  #: the table stands on the floor again


class CarryTable:
    """Carry a table with a person (Cosero §7.3.3).

    The robot holds its end; it reads the table's pitch (positive: the person's end is
    higher). A pitch over ``lift_pitch`` starts the carry. While carrying, the hand's
    height follows the person's end: the behaviour estimates the person's end's height
    (its own hand's height plus ``length · sin(pitch)``) and vertical speed with an
    alpha-beta filter over the noisy pitch, and moves the hand's target at that speed
    (feedforward) plus ``level_gain`` per second on the remaining height difference. The
    torso lift carries the height change (``torso``: its height at the grasp), so the
    arm keeps its posture and its reach; x, y and yaw are compliant and the base drives
    and turns to bring the hand back to its grasping pose. Once the person's end goes
    down past ``-lift_pitch`` after the table was up, the robot lowers with them (still
    levelling, and at least ``settle_speed``) until the floor holds its end up: the hand
    stays above its target while the person's end is back near the floor. The person's
    end going down (its estimated speed), with the table pitched down or their end below
    half the height it was carried at (the robot may follow so closely that the table
    never pitches), tells lowering from an overshoot of the robot's.
    """

    def __init__(self, hand_position: np.ndarray, hand_rotation: np.ndarray, *,
                 length: float, lift_pitch: float = 0.02, level_gain: float = 8.0,
                 max_lift_speed: float = 0.6, turn_gain: float = 1.0,
                 torso: float | None = None, torso_range: tuple[float, float] = (0.0, 0.5),
                 alpha: float = 0.2, beta: float = 0.02) -> None:
        self.start = np.asarray(hand_position, dtype=float).copy()
        self.target = self.start.copy()
        self.rotation = np.asarray(hand_rotation, dtype=float)
        self.length, self.lift_pitch = length, lift_pitch
        self.level_gain, self.max_lift_speed = level_gain, max_lift_speed
        self.turn_gain = turn_gain
        self.torso, self.torso_range = torso, torso_range
        self.alpha, self.beta = alpha, beta
        self.settle_speed = 0.05  #: m/s the hand goes down at least while lowering
        self.follow = GuidedByHand(hand_position, hand_rotation, gain=8.0, speed=0.6,
                                   turn_gain=0.0)
        self.phase = CarryPhase.WAITING
        self.highest = 0.0
        planar = self.follow.compliance.axes
        self.compliance = Compliance().with_axes(
            x=planar[0], y=planar[1],
            yaw=AxisCompliance(stiffness=40.0, damping=2.0, max_force=6.0, min_force=0.2,
                               span=0.5, positive=True, negative=True),
            pitch=AxisCompliance(stiffness=30.0, damping=2.0, max_force=4.0, min_force=0.2,
                                 span=0.5, positive=True, negative=True))
        self.max_pitch = 0.0
        self.other: tuple[float, float] | None = None  #: the person's end: height, speed
        self.confirm = 0.1  #: seconds the person's end must go down to start lowering
        self._down_for = 0.0

    def _track(self, dt: float, hand_z: float, pitch: float) -> tuple[float, float]:
        """The alpha-beta filter over the person's end's height (base frame)."""
        seen = hand_z + self.length * math.sin(pitch)
        if self.other is None:
            self.other = (seen, 0.0)
        height, speed = self.other
        predicted = height + speed * dt
        residual = seen - predicted
        self.other = (predicted + self.alpha * residual, speed + self.beta * residual / dt)
        return self.other

    def update(self, dt: float, shift: np.ndarray, pitch: float) -> Command:
        """``pitch``: the table's pitch as the robot perceives it (rad)."""
        base = Twist()
        other_height, other_speed = self._track(dt, float(self.target[2] + shift[2]), pitch)
        if self.phase is CarryPhase.WAITING and pitch > self.lift_pitch:
            self.phase = CarryPhase.CARRYING
        if self.phase is CarryPhase.CARRYING:
            self.highest = max(self.highest, self.target[2] - self.start[2])
            halfway = other_height < self.start[2] + 0.5 * self.highest
            going_down = self.highest > 0.05 and (pitch < -self.lift_pitch or halfway) and \
                other_speed < -self.settle_speed
            self._down_for = self._down_for + dt if going_down else 0.0
            if self._down_for >= self.confirm:  # their end goes down, not a wobble
                self.phase = CarryPhase.LOWERING
        if self.phase in (CarryPhase.CARRYING, CarryPhase.LOWERING):
            rate = other_speed + self.level_gain * self.length * math.sin(pitch)
            if self.phase is CarryPhase.LOWERING:  # down, at least slowly, to the floor
                rate = min(rate, -self.settle_speed)
            rate = max(-self.max_lift_speed, min(self.max_lift_speed, rate))
            self.target[2] = max(self.start[2] - 0.05, self.target[2] + rate * dt)
        if self.phase is CarryPhase.CARRYING:  # realign the hand: the base follows
            planar = self.follow.update(shift).base
            base = Twist(planar.vx, planar.vy, self.turn_gain * float(shift[5]))
        if self.phase is CarryPhase.LOWERING and float(shift[2]) > 0.015 and \
                other_height < self.start[2] + 0.05:
            # The hand is held above its target, the person's end is down: the table
            # stands on its legs.
            self.phase = CarryPhase.DONE
            self.target[2] = self.target[2] + float(shift[2])
        self.max_pitch = max(self.max_pitch, abs(pitch))
        torso = None
        if self.torso is not None:  # the torso carries the height change
            low, high = self.torso_range
            torso = min(high, max(low, self.torso + float(self.target[2] - self.start[2])))
        return Command(self.target.copy(), self.rotation, self.compliance, gripper_closed=True,
                       base=base, torso=torso)


class DoorPhase(StrEnum):
    """Where a ``DoorMotion`` is."""

    OPENING = "opening"  #: pulling the handle round the hinge
    OPEN = "open"  #: opened as far as asked
    CLOSING = "closing"  #: pushing it back round the hinge
    CLOSED = "closed"  #: against its frame: the hand cannot push it further


class DoorMotion:
    """Open a door by its handle and close it again, under compliance (Cosero §4.2).

    The robot holds the handle and knows roughly where the hinge is (``hinge``: a point
    in the odometry frame, from its door model and what it saw; it may be centimetres
    off). Every tick it takes the hand's actual position, measures how far round the
    estimated hinge it has come (the opening angle) and sets the hand's target on the
    circle through the hand, ``speed`` further round (at most ``lead`` metres ahead of
    the hand), with the hand's yaw turned by the same angle. The true handle moves on
    a circle the robot does not know exactly: the hand is compliant in the plane and in
    yaw, so where the estimate is wrong the door's hinge, not the arm, sets the path;
    and since the target is re-set from the hand's actual radius every tick, the error
    never accumulates. The base drives (and turns) to keep the target at the hand's
    place in front of it. It opens until the estimated angle reaches ``goal`` (rad),
    then, once ``close`` is called, pushes the door back round the hinge until the hand
    stalls near angle 0: the door is against its frame.
    """

    def __init__(self, hinge: tuple[float, float], pose: tuple[float, float, float],
                 hand_position: np.ndarray, hand_rotation: np.ndarray, *,
                 goal: float = 1.2, speed: float = 0.15, lead: float = 0.06,
                 base_gain: float = 2.0, base_speed: float = 0.3,
                 turn_gain: float = 1.0, keep_radius: bool = False) -> None:
        self.hinge = np.asarray(hinge, dtype=float)
        self.keep_radius = keep_radius
        self.home = np.asarray(hand_position, dtype=float).copy()  #: base frame
        self.rotation = np.asarray(hand_rotation, dtype=float)
        self.goal, self.speed, self.lead = goal, speed, lead
        self.base_gain, self.base_speed, self.turn_gain = base_gain, base_speed, turn_gain
        start = to_odometry(pose, self.home)[:2] - self.hinge
        self.radius = float(np.linalg.norm(start))
        self.start_bearing = math.atan2(float(start[1]), float(start[0]))
        # Which way round opens: the way that first brings the handle towards the robot.
        heading = np.array([math.cos(pose[2]), math.sin(pose[2])])
        ccw = np.array([-start[1], start[0]]) / self.radius
        self.turn = -1.0 if float(np.dot(ccw, heading)) > 0 else 1.0
        both = {"positive": True, "negative": True}
        planar = _soft(0.15, 3.0, 40.0, damping=30.0)
        self.compliance = Compliance().with_axes(
            x=AxisCompliance(**{**planar.__dict__, **both}),
            y=AxisCompliance(**{**planar.__dict__, **both}),
            yaw=AxisCompliance(stiffness=20.0, damping=1.5, max_force=4.0, min_force=0.2,
                               span=0.6, **both))
        self.phase = DoorPhase.OPENING
        self.commanded = 0.0  #: the target's angle round the hinge (rad, opening positive)
        self.angle = 0.0  #: the hand's angle round the estimated hinge
        self._stalled = 0.0
        self._last = 0.0
        self.yaw0 = pose[2]  #: the base's heading when it took the handle

    def close(self) -> None:
        """Start closing the door (after it is open)."""
        self.phase = DoorPhase.CLOSING

    def update(self, dt: float, pose: tuple[float, float, float],
               hand_position: np.ndarray) -> Command:
        """``pose``: the base's odometry (x, y, yaw); ``hand_position``: base frame."""
        hand = to_odometry(pose, np.asarray(hand_position, dtype=float))
        offset = hand[:2] - self.hinge
        radius = float(np.linalg.norm(offset))
        bearing = math.atan2(float(offset[1]), float(offset[0]))
        self.angle = self.turn * wrap_angle(bearing - self.start_bearing)
        step = self.speed / max(self.radius, 0.2) * dt
        ahead = self.lead / max(radius, 0.2)
        if self.phase is DoorPhase.OPENING:
            self.commanded = min(self.commanded + step, self.angle + ahead, self.goal)
            if self.angle >= self.goal - 0.02:
                self.phase = DoorPhase.OPEN
        elif self.phase is DoorPhase.CLOSING:
            self.commanded = max(self.commanded - step, self.angle - ahead, -0.05)
            moving = abs(self.angle - self._last) / dt > 0.02
            self._stalled = 0.0 if moving or self.angle > 0.15 else self._stalled + dt
            if self._stalled >= 0.3:
                self.phase = DoorPhase.CLOSED
        self._last = self.angle
        if self.phase in (DoorPhase.OPEN, DoorPhase.CLOSED):
            self.commanded = self.angle if self.phase is DoorPhase.CLOSED else self.commanded
        turned = self.start_bearing + self.turn * self.commanded
        if self.keep_radius:  # the hand slid along what it holds: back to where it took it
            radius = self.radius
        target = np.array([self.hinge[0] + radius * math.cos(turned),
                           self.hinge[1] + radius * math.sin(turned), float(hand[2])])
        target[2] = float(to_odometry(pose, self.home)[2])
        yaw = self.turn * self.commanded  #: the handle has turned with the door
        # The base brings the target to the hand's place before it and faces the handle.
        place = to_odometry(pose, self.home)
        error = target[:2] - place[:2]
        c, s = math.cos(pose[2]), math.sin(pose[2])
        local = np.array([c * error[0] + s * error[1], -s * error[0] + c * error[1]])
        local = self.base_gain * local
        norm = float(np.linalg.norm(local))
        if norm > self.base_speed:
            local *= self.base_speed / norm
        heading_error = wrap_angle(yaw - pose[2] + self.yaw0)
        base = Twist(float(local[0]), float(local[1]), self.turn_gain * heading_error)
        if self.phase is DoorPhase.CLOSED:
            base = Twist()
        target_base = to_base(pose, target)
        relative_yaw = wrap_angle(yaw + self.yaw0 - pose[2])
        rotation = yaw_rotation(relative_yaw) @ self.rotation
        return Command(target_base, rotation, self.compliance, gripper_closed=True, base=base)


def to_odometry(pose: tuple[float, float, float], point: np.ndarray) -> np.ndarray:
    """A base-frame point in the odometry frame."""
    moved: np.ndarray = yaw_rotation(pose[2]) @ np.asarray(point, dtype=float) + np.array(
        [pose[0], pose[1], 0.0])
    return moved


def to_base(pose: tuple[float, float, float], point: np.ndarray) -> np.ndarray:
    """An odometry-frame point in the base frame."""
    local: np.ndarray = yaw_rotation(pose[2]).T @ (np.asarray(point, dtype=float) -
                                                  np.array([pose[0], pose[1], 0.0]))
    return local
