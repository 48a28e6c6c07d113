"""Opening a shut door with the arm (Cosero §4.2), through the Body port alone.

The robot looks at the door with its head camera (three pans of the head, merged: from
before a door the leaf is wider than one view) and finds the leaf, the handle and the
hinge in the depth points (``homebot.perception.door_leaf``); which way the leaf swings
comes from its map (the world file's ``swings_into``, else the door's first room). It
then works in its odometry frame, which drifts little over the metre this takes:

1. steps before the handle, at a comfortable reach, a little towards the hinge (the handle
   comes round towards that side as the door opens);
2. brings the open hand to the handle, fingers above and below the lever, and closes them
   (the gripper's width says whether it holds something);
3. presses the lever down round its pivot (the handle's end nearest the latch), turning
   the hand with it, which draws the latch;
4. pulls the door round the hinge it saw (``homebot.manipulation.interaction.DoorMotion``):
   each tick the hand's target is set on the circle through where the hand truly is, and
   the arm follows it from its measured joints, so it yields to the force the hinge gives
   and the door's true circle prevails over the robot's estimate; the base backs away,
   straight, as the handle comes nearer (Cosero's way), and the arm follows it aside;
5. lets go once it believes the door is open by ``_OPEN_ENOUGH`` (or the lever slipped
   from its fingers), draws the hand back and up, tucks the arm, and leaves the check to
   the laser.

A leaf that does not turn (locked, or held), a lost handle, a hand that cannot reach, or
a door that opens away from the robot (its arm cannot push a leaf past the doorway it
cannot yet enter) end the attempt with a reason, and the caller asks someone instead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from homebot.geometry import Pose, wrap_angle
from homebot.manipulation.grasps import IK_SEEDS
from homebot.manipulation.ik import rotation_error, solve_ik
from homebot.manipulation.interaction import DoorMotion, DoorPhase, to_base, to_odometry
from homebot.manipulation.pick import GRIP_FORCE, TUCKED, current_configuration, follow
from homebot.manipulation.scene import Obstacle, PlanningScene
from homebot.navigation.straight import drive_straight
from homebot.perception.door_leaf import SeenDoor, perceive_door
from homebot.robot import Body, DriveKind, JointTarget, Twist
from homebot.world import World

__all__ = ["DoorAttempt", "DoorOpening"]

_PANS = (-0.45, 0.0, 0.45)  #: radians the head turns to take in the whole leaf
_TILT = 0.25  #: radians the head looks down at the door
_MAP_AGREES = 0.35  #: metres between the seen door's middle and the map's
_REACH = 0.75  #: metres in front of the base where the hand takes the handle
_TOWARDS_HINGE = 0.3  #: metres the robot stands aside from the handle, towards the hinge
#: arm configurations (torso first) with the hand level in front, fingers closing up and
#: down, from which the inverse kinematics starts
_HANDLE_SEEDS = (np.array([0.25, 0.0, 1.25, 0.0, -2.05, 0.0, 0.75, 1.57]),
                 np.array([0.25, 0.0, 1.25, 0.0, -2.05, 0.0, 0.75, -1.57]))
_TOWARDS_FREE_END = 0.01  #: metres from the handle's middle towards its free end
_LEAF_HALF_THICKNESS = 0.02  #: metres: half a door leaf's thickness
_HANDLE_DEPTH = 0.025  #: metres: a lever's depth; the camera sees its front
_PRE_GRASP = 0.08  #: metres back from the handle where the hand stops before going in
_HAND_OPEN = 0.08  #: metres between the fingers, coming up to the lever
_HOLDING = 0.006  #: metres: fingers closer than this hold nothing
_EMPTY_FOR = 0.15  #: seconds the fingers must stand closed for the handle to be lost
_PRESS_ANGLE = 0.55  #: radians the hand turns a lever down (its stop may end it sooner)
_PRESS_SECONDS = 0.8
_PULL_SPEED = 0.05  #: m/s the handle's target goes round the hinge
_PULL_LEAD = 0.02  #: metres the handle's target leads the hand by at most
_BASE_SPEED = 0.06  #: m/s the base backs away at most while the hand holds the handle
_BASE_GAIN = 1.5  #: per second, on how much nearer than at the start the handle's target is
_OPEN_ENOUGH = 1.45  #: radians the robot opens the door to (it counts past 1.2 as open)
_TIME_LIMIT = 25.0  #: seconds of pulling before the robot gives up
_MOVED = 0.2  #: radians the hand must have come round (a hand slipping along a lever held
#: shut comes round some way too) for the door not to count as held shut
_STALL = (2.0, 0.03)  #: seconds within which the door must turn this many radians
_JOINT_STEP = 0.08  #: radians the arm's command may lead its joints by in one tick
_DRAW_BACK_SECONDS = 1.6  #: the hand draws back off the handle and rises over it
_LIFT_OFF = 0.25  #: metres the hand rises before it is tucked
_TURN_TOLERANCE = 0.03  #: radians: the base's final heading this close will do
_POSTURE_GAIN = 0.2  #: of the way back to the posture, per tick, in the null space


@dataclass(frozen=True)
class DoorAttempt:
    """How an attempt went: ``reason`` is None when the robot swung the door open as far
    as it meant to (whether it is open, the laser says); else why it stopped."""

    reason: str | None
    seconds: float
    believed_degrees: float = 0.0  #: how far round its hinge estimate the hand came


class DoorOpening:
    """The arm opens shut doors (see the module's docstring).

    Args:
        body: the drivers.
        world: the robot's map (where doors are, which way they swing).
        rng: seeds the perception's RANSAC.
    """

    def __init__(self, body: Body, world: World, rng: np.random.Generator) -> None:
        self.body = body
        self.world = world
        self.rng = rng
        self._posture: np.ndarray | None = None  #: the arm's configuration at the handle

    # ------------------------------------------------------------ looking

    def look(self) -> SeenDoor | None:
        """The door before the robot, from three head pans merged (base frame)."""
        body = self.body
        clouds = []
        for pan in _PANS:
            body.point_head(pan, _TILT)
            body.tick()
            clouds.append(body.camera().points()[0])
        body.point_head(0.0, 0.0)
        return perceive_door(np.concatenate(clouds), self.rng)

    def open(self, door: str, estimate: Pose) -> DoorAttempt:
        """Open ``door``, which the robot stands before (``estimate``: its pose on the map)."""
        began = self.body.now()
        model = self.world.doors[door]
        here = self.world.room_at(estimate.x, estimate.y)
        swings_into = model.swings_into or model.rooms[0]
        if here is not None and here != swings_into:
            return DoorAttempt("it opens away from me, and my arm cannot push it open", 0.0)
        start = self.body.odometry().pose
        seen = self.look()
        if seen is None:
            return DoorAttempt("I do not see its leaf and handle", self.body.now() - began)
        middle = to_odometry(_triple(start), np.array([*(seen.hinge + seen.latch) / 2, 0.0]))
        on_map = _map_to_odometry(estimate, start, model.position)
        if math.dist(middle[:2], on_map) > _MAP_AGREES:
            return DoorAttempt("the door I see is not where my map has it",
                               self.body.now() - began)
        door_frame = _DoorInOdometry.of(seen, _triple(start))
        reason = self._take_handle(door_frame)
        if reason is not None:
            self._let_go()
            return DoorAttempt(reason, self.body.now() - began)
        reason, believed = self._pull(door_frame)
        self._let_go()
        return DoorAttempt(reason, self.body.now() - began, math.degrees(believed))

    # ------------------------------------------------------------ the handle

    def _take_handle(self, door: _DoorInOdometry) -> str | None:
        """Step before the handle and grasp it; None, or why not."""
        body = self.body
        grasp = door.handle - _TOWARDS_FREE_END * door.along3 - \
            _HANDLE_DEPTH / 2 * door.normal3
        # Before the handle, a little towards the hinge: the handle comes round towards the
        # robot and the hinge's side as the door opens, through the arm's middle reach.
        stand = grasp[:2] + _REACH * door.normal - _TOWARDS_HINGE * door.along3[:2]
        heading = math.atan2(-door.normal[1], -door.normal[0])
        if not self._drive_to((float(stand[0]), float(stand[1])), heading):
            return "I cannot get to the handle"
        pose = _triple(body.odometry().pose)
        hand = to_base(pose, grasp)
        # The wrist rolled the way that leaves it travel to turn towards the hinge (the
        # fingers are alike: up and down are the same grasp).
        hinge_left = float(to_base(pose, np.array([*door.hinge, 0.0]))[1]) > float(hand[1])
        rotation = _grasp_rotation(to_base(pose, grasp - door.normal3)[:2] - hand[:2],
                                   1.0 if hinge_left else -1.0)
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0),
                              [door.leaf_obstacle(pose)])
        approach = rotation[:, 0]
        seeds = list(_HANDLE_SEEDS if hinge_left else _HANDLE_SEEDS[::-1])
        before = solve_ik(scene, hand - _PRE_GRASP * approach, rotation, [*seeds, *IK_SEEDS])
        if before is None:
            return "my hand cannot reach the handle"
        at = solve_ik(scene, hand, rotation, [before], posture=before)
        if at is None or scene.collides(before, gripper=_HAND_OPEN):
            return "my hand cannot reach the handle"
        body.gripper().command(_HAND_OPEN)
        follow(body, [current_configuration(body), before])
        follow(body, [before, at])
        self._posture = at
        body.gripper().command(0.0, GRIP_FORCE)
        body.tick(max(1, round(0.6 / body.tick_period)))
        if body.gripper().state().width < _HOLDING:
            return "my fingers closed on nothing: I missed the handle"
        pivot = to_base(pose, door.handle_end)
        self._press(scene, rotation, pivot, to_base(pose, grasp + door.normal3)[:2] -
                    hand[:2])
        if body.gripper().state().width < _HOLDING:
            return "the handle slipped from my fingers"
        return None

    def _press(self, scene: PlanningScene, rotation: np.ndarray, pivot: np.ndarray,
               normal: np.ndarray) -> None:
        """Press the lever down round its ``pivot`` (base frame), about the leaf's
        ``normal``: the hand goes round with it, turning as the lever turns."""
        from scipy.spatial.transform import Rotation

        body = self.body
        start, _ = scene.grasp_frame(current_configuration(body))
        arm = start - pivot
        axis = np.array([normal[0], normal[1], 0.0]) / np.linalg.norm(normal)
        # the way round that takes the hand (on the lever's free end) down
        down = -1.0 if float(np.cross(axis, arm)[2]) > 0 else 1.0
        ticks = max(1, round(_PRESS_SECONDS / body.tick_period))
        for k in range(1, ticks + 1):
            turn = Rotation.from_rotvec(down * _PRESS_ANGLE * k / ticks * axis).as_matrix()
            self._step_towards(scene, pivot + turn @ arm, turn @ rotation)
            body.tick()
        body.tick(max(1, round(0.2 / body.tick_period)))

    # ------------------------------------------------------------ the pull

    def _pull(self, door: _DoorInOdometry) -> tuple[str | None, float]:
        """Pull the door round its hinge; (None, angle) once open far enough, else why not."""
        body = self.body
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0))
        hand, rotation = scene.grasp_frame(current_configuration(body))
        # the hinge's axis lies in the leaf's middle, behind the face the camera saw
        hinge = door.hinge - _LEAF_HALF_THICKNESS * door.normal
        motion = DoorMotion((float(hinge[0]), float(hinge[1])),
                            _triple(body.odometry().pose), hand, rotation,
                            goal=_OPEN_ENOUGH, speed=_PULL_SPEED, lead=_PULL_LEAD,
                            keep_radius=True)
        dt = body.tick_period
        began = body.now()
        progress = (began, 0.0)
        empty = 0  #: ticks in a row the fingers have stood closed on nothing
        while True:
            pose = _triple(body.odometry().pose)
            hand, _ = scene.grasp_frame(current_configuration(body))
            command = motion.update(dt, pose, hand)
            body.command_velocity(_backing(command.hand_position, motion.home))
            self._step_towards(scene, command.hand_position, command.hand_rotation)
            body.tick()
            empty = empty + 1 if body.gripper().state().width < _HOLDING else 0
            if empty * dt >= _EMPTY_FOR:  # pulled out of the fingers; by a door that held?
                return ("the door does not move: it may be locked" if motion.angle < _MOVED
                        else "the handle slipped from my fingers"), motion.angle
            if motion.phase is DoorPhase.OPEN:
                return None, motion.angle
            if motion.angle > progress[1] + _STALL[1]:
                progress = (body.now(), motion.angle)
            elif body.now() - progress[0] > _STALL[0]:
                return ("the door does not move: it may be locked" if motion.angle < _MOVED
                        else "the door stopped turning"), motion.angle
            if body.now() - began > _TIME_LIMIT:
                return "the door took too long to open", motion.angle

    def _step_towards(self, scene: PlanningScene, position: np.ndarray,
                      rotation: np.ndarray) -> None:
        """Command the joints a step from where they are towards the hand pose (base
        frame): from the measured joints, so what pushes the hand off its target moves
        the next target too, and the arm yields to it (the joints' servos are springs)."""
        q = current_configuration(self.body)
        scene.set(q)
        here, turn = scene.site()
        error = np.concatenate((position - here, rotation_error(turn, rotation)))
        jacobian = scene.jacobian()
        jacobian[:, 0] = 0.0  # the torso stays
        inverse = jacobian.T @ np.linalg.inv(jacobian @ jacobian.T + 1e-3 * np.eye(6))
        step = inverse @ error
        if self._posture is not None:  # the redundant joint keeps the arm near its posture
            step += (np.eye(len(q)) - inverse @ jacobian) @ (_POSTURE_GAIN * (self._posture - q))
        largest = float(np.max(np.abs(step)))
        if largest > _JOINT_STEP:
            step *= _JOINT_STEP / largest
        target = np.clip(q + step, scene.lower, scene.upper)
        self.body.arm().command(JointTarget(tuple(float(v) for v in target[1:]),
                                            torso=float(q[0])))

    def _let_go(self) -> None:
        """Open the fingers, draw the hand back from the door and tuck the arm."""
        body = self.body
        body.command_velocity(Twist())
        body.gripper().command(0.2)
        body.tick(max(1, round(0.5 / body.tick_period)))
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0))
        hand, rotation = scene.grasp_frame(current_configuration(body))
        ticks = max(1, round(_DRAW_BACK_SECONDS / body.tick_period))
        for k in range(1, ticks + 1):  # straight back off the handle, then up over it
            back = hand - _PRE_GRASP * min(1.0, 2 * k / ticks) * rotation[:, 0] + \
                np.array([0.0, 0.0, _LIFT_OFF * max(0.0, 2 * k / ticks - 1.0)])
            self._step_towards(scene, back, rotation)
            body.tick()
        follow(body, [current_configuration(body), TUCKED])

    # ------------------------------------------------------------ the base

    def _drive_to(self, point: tuple[float, float], heading: float) -> bool:
        """Drive (odometry frame) straight to ``point`` and turn to ``heading``."""
        body = self.body

        def odometry() -> Pose:
            return body.odometry().pose

        here = odometry()
        if math.dist(here.xy(), point) > 0.03:
            if body.drive is DriveKind.OMNIDIRECTIONAL:
                self._slide_to(point)
            elif not drive_straight(body, odometry, here.xy(), point):
                return False
        for _ in range(int(4 * math.pi / (body.limits.angular * body.tick_period)) + 1):
            error = wrap_angle(heading - odometry().theta)
            if abs(error) <= _TURN_TOLERANCE:
                break
            limit = math.sqrt(2 * body.limits.angular_acceleration * abs(error))
            body.command_velocity(Twist(0.0, 0.0, math.copysign(
                min(body.limits.angular, limit, 0.6), error)))
            body.tick()
        body.command_velocity(Twist())
        body.tick()
        return math.dist(odometry().xy(), point) < 0.08

    def _slide_to(self, point: tuple[float, float]) -> None:
        """An omnidirectional base slides to ``point`` without turning."""
        body = self.body
        for _ in range(int(10.0 / body.tick_period)):
            pose = body.odometry().pose
            local = to_base(_triple(pose), np.array([point[0], point[1], 0.0]))[:2]
            distance = float(np.linalg.norm(local))
            if distance < 0.02:
                break
            speed = min(0.2, 1.5 * distance)
            body.command_velocity(Twist(speed * local[0] / distance,
                                        speed * local[1] / distance, 0.0))
            body.tick()
        body.command_velocity(Twist())


@dataclass(frozen=True)
class _DoorInOdometry:
    """The seen door in the odometry frame."""

    hinge: np.ndarray  #: (2,)
    latch: np.ndarray  #: (2,)
    normal: np.ndarray  #: (2,) unit, towards the side the robot looked from
    handle: np.ndarray  #: (3,)
    handle_end: np.ndarray  #: (3,) the handle's end nearest the latch: its pivot

    @classmethod
    def of(cls, seen: SeenDoor, pose: tuple[float, float, float]) -> _DoorInOdometry:
        c, s = math.cos(pose[2]), math.sin(pose[2])
        turn = np.array([[c, -s], [s, c]])
        return cls(turn @ seen.hinge + pose[:2], turn @ seen.latch + pose[:2],
                   turn @ seen.normal, to_odometry(pose, seen.handle),
                   to_odometry(pose, seen.handle_end))

    @property
    def along3(self) -> np.ndarray:
        """(3,) unit vector along the leaf from the hinge to the latch edge."""
        along = (self.latch - self.hinge) / np.linalg.norm(self.latch - self.hinge)
        return np.array([along[0], along[1], 0.0])

    @property
    def normal3(self) -> np.ndarray:
        return np.array([self.normal[0], self.normal[1], 0.0])

    def leaf_obstacle(self, pose: tuple[float, float, float]) -> Obstacle:
        """The leaf as a box in the planning scene of a base at ``pose`` (odometry)."""
        middle = to_base(pose, np.array([*(self.hinge + self.latch) / 2, 1.0]))
        along = to_base(pose, np.array([*self.latch, 0.0]))[:2] - \
            to_base(pose, np.array([*self.hinge, 0.0]))[:2]
        width = float(np.linalg.norm(along))
        return Obstacle("door leaf", "box", (width, 0.04, 2.0),
                        (float(middle[0]), float(middle[1]), 1.0),
                        math.atan2(float(along[1]), float(along[0])))


def _grasp_rotation(towards: np.ndarray, up: float) -> np.ndarray:
    """The hand's rotation (base frame) pointing horizontally along ``towards`` (2,),
    fingers closing up and down (on a lever); its y axis up (``up`` 1) or down (-1)."""
    x = np.array([towards[0], towards[1], 0.0])
    x /= np.linalg.norm(x)
    y = np.array([0.0, 0.0, up])
    return np.column_stack((x, y, np.cross(x, y)))


def _backing(target: np.ndarray, home: np.ndarray) -> Twist:
    """Cosero's way (§4.2): the base backs away, straight, as the handle's target (base
    frame) comes nearer than ``home``, where the hand took it; slowly, since the fingers
    hold the lever by friction. The arm follows the handle to the side."""
    nearer = float(home[0] - target[0])
    return Twist(-min(_BASE_SPEED, max(0.0, _BASE_GAIN * nearer)), 0.0, 0.0)


def _triple(pose: Pose) -> tuple[float, float, float]:
    return (pose.x, pose.y, pose.theta)


def _map_to_odometry(estimate: Pose, odometry: Pose, point: tuple[float, float]
                     ) -> np.ndarray:
    """A map point in the odometry frame, by the robot's pose on both."""
    local = to_base(_triple(estimate), np.array([point[0], point[1], 0.0]))
    return to_odometry(_triple(odometry), local)[:2]
