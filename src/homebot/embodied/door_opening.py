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
   the hand with it, which draws the latch.

A leaf that swings towards the robot is then
4. pulled ajar round the hinge it saw (``homebot.manipulation.interaction.DoorMotion``, to
   ``_AJAR``): each tick the hand's target is set on the circle through where the hand
   truly is, and the arm follows it from its measured joints, so it yields to the force
   the hinge gives and the door's true circle prevails over the robot's estimate; the base
   backs away, straight, as the handle comes nearer (Cosero's way);
5. let go: pulled further, the leaf's face turns away from a robot on the latch side and
   the lever slips from fingers that hold it by friction alone. The hand draws back, goes
   out past the leaf's free edge, round it, and in behind the far face, well behind where
   the robot believes the leaf is; then it sweeps round the hinge, meets the face wherever
   the leaf truly stands and pushes it to ``_PUSH_GOAL`` while the base backs away.

A leaf that swings away from the robot is instead
4. nudged out of its frame by the pressed lever (the latch stays drawn once it has left);
5. let go; the base steps up to the doorway and the fingertips push the near face round.

Last, the hand draws back out of the doorway and up, the arm tucks, and the laser says
whether the door is open. A leaf that does not turn (locked, or held), a lost handle or a
hand that cannot reach end the attempt with a reason, and the caller asks someone instead.
"""

from __future__ import annotations

import math
from collections.abc import Callable
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
_SETTLE = 0.5  #: seconds the base stands still before the robot looks
_BEFORE = 0.6  #: metres before the door's middle from where the robot looks at it
_BEFORE_TOLERANCE = 0.15  #: metres or radians off that pose the robot looks from as it is
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
_PULL_SPEED = 0.07  #: m/s the handle's target goes round the hinge
_PULL_LEAD = 0.02  #: metres the handle's target leads the hand by at most
_BASE_SPEED = 0.06  #: m/s the base backs away at most while the hand holds the handle
_BASE_GAIN = 1.5  #: per second, on how much nearer than at the start the handle's target is
_AJAR = 0.7  #: radians the hand pulls the leaf round by the lever before it lets go
#: radians the leaf must stand ajar for the hand to come round its edge (the lever may slip
#: from the fingers before ``_AJAR``)
_PUSH_FROM = 0.4
_PUSH_GOAL = 1.65  #: radians round the hinge the hand pushes the leaf's back face to
_BEHIND = 0.2  #: radians behind the believed leaf where the hand comes in to push it
_DRAW_BACK = 0.12  #: metres the hand draws back off the lever it lets go of
_FRONT = 0.2  #: radians before the believed leaf where the hand goes out past its edge
_EDGE_CLEAR = 0.12  #: metres beyond the leaf's free edge the hand goes round it
_HAND_TILT = 0.35  #: radians the pushing hand turns off the leaf's face
_IN_FROM_EDGE = 0.08  #: metres in from the free edge where the hand pushes the leaf
_PUSH_SPEED = 0.12  #: m/s the pushing hand goes round the hinge
_PUSH_LEAD = 0.1  #: radians the pushing hand's target leads the hand by at most
_EDGE_AHEAD = 0.65  #: metres before the base where the hand goes round the leaf's edge
_PUSH_AHEAD = 0.55  #: metres before the base the pushing hand stays (the base backs)
_PUSH_LIMIT = 15.0  #: seconds of pushing before the robot stops
_NUDGE = 0.08  #: radians the hand pushes a leaf that swings away round by its lever
_AWAY_STAND = 0.42  #: metres from a leaf that swings away to the base's middle, pushing it
_AWAY_RADIUS = 0.42  #: metres from the hinge where the fingertips push a leaf away
_AWAY_BEHIND = 0.25  #: radians before the leaf's face where the fingertips come in
_AWAY_LEAD = 0.2  #: radians the fingertips' target leads the hand by at most
_AWAY_GOAL = 1.4  #: radians round the hinge the fingertips push a leaf away to
_TIME_LIMIT = 25.0  #: seconds of pulling before the robot gives up
_MOVED = 0.2  #: radians the hand must have come round (a hand slipping along a lever held
#: shut comes round some way too) for the door not to count as held shut
_STALL = (2.0, 0.03)  #: seconds within which the door must turn this many radians
_JOINT_STEP = 0.08  #: radians the arm's command may lead its joints by in one tick
_DRAW_BACK_SECONDS = 1.6  #: the hand draws back off the handle and rises over it
_LIFT_OFF = 0.25  #: metres the hand rises before it is tucked
#: metres to the side of the base within which it steps straight (back) to a point
_ALONG_ENOUGH = 0.06
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
        """The door before the robot, from three head pans merged (base frame), the base
        at rest (views taken as it rolls on do not line up)."""
        body = self.body
        body.command_velocity(Twist())
        body.tick(max(1, round(_SETTLE / body.tick_period)))
        clouds = []
        for pan in _PANS:
            body.point_head(pan, _TILT)
            body.tick()
            clouds.append(body.camera().points()[0])
        body.point_head(0.0, 0.0)
        return perceive_door(np.concatenate(clouds), self.rng)

    def looking_pose(self, door: str, estimate: Pose) -> Pose:
        """Where (on the map) the robot looks at ``door`` from: straight before it, facing
        it, on the side the robot is (``estimate``: its pose on the map)."""
        room_here = self.world.room_at(estimate.x, estimate.y)
        return min((self.world.point_before_door(door, room, _BEFORE)
                    for room in self.world.doors[door].rooms),
                   key=lambda before: (self.world.room_at(before.x, before.y) != room_here,
                                       math.dist(estimate.xy(), before.xy())))

    def open(self, door: str, estimate: Pose) -> DoorAttempt:
        """Open ``door``, which the robot stands before (``estimate``: its pose on the map)."""
        began = self.body.now()
        model = self.world.doors[door]
        before = self.looking_pose(door, estimate)
        away = self.world.room_at(before.x, before.y) != (model.swings_into or model.rooms[0])
        # Face the door from straight before it, where the leaf fills the head camera's
        # views (navigation may leave the robot beside the door, or turned away).
        start = self.body.odometry().pose
        on_map = _map_to_odometry(estimate, start, model.position)
        if math.dist(estimate.xy(), before.xy()) > _BEFORE_TOLERANCE or \
                abs(wrap_angle(before.theta - estimate.theta)) > _BEFORE_TOLERANCE:
            spot = _map_to_odometry(estimate, start, before.xy())
            self._drive_to((float(spot[0]), float(spot[1])),
                           start.theta + wrap_angle(before.theta - estimate.theta))
        looked_from = self.body.odometry().pose
        seen = self.look() or self.look()  # a second look, should people have been in the way
        if seen is None:
            return DoorAttempt("I do not see its leaf and handle", self.body.now() - began)
        middle = to_odometry(_triple(looked_from),
                             np.array([*(seen.hinge + seen.latch) / 2, 0.0]))
        if math.dist(middle[:2], on_map) > _MAP_AGREES:
            return DoorAttempt("the door I see is not where my map has it",
                               self.body.now() - began)
        door_frame = _DoorInOdometry.of(seen, _triple(looked_from))
        reason = self._take_handle(door_frame)
        if reason is not None:
            self._let_go()
            return DoorAttempt(reason, self.body.now() - began)
        if away:
            reason, believed = self._push_away(door_frame)
            self._let_go()
            return DoorAttempt(reason, self.body.now() - began, math.degrees(believed))
        reason, believed = self._pull(door_frame)
        if believed < _PUSH_FROM:  # the leaf did not come round far enough to get behind it
            self._let_go()
            return DoorAttempt(reason or "the door stopped turning", self.body.now() - began,
                               math.degrees(believed))
        # Ajar: the lever would slip from the fingers as the leaf's face turns away, so the
        # hand lets go, comes round the leaf's free edge and pushes its far face round.
        reason, believed = self._push(door_frame, believed)
        self._withdraw(door_frame)
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
                            goal=_AJAR, speed=_PULL_SPEED, lead=_PULL_LEAD,
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

    # ------------------------------------------------------------ the push

    def _push(self, door: _DoorInOdometry, believed: float) -> tuple[str | None, float]:
        """Let go of the lever of a leaf ajar by about ``believed`` radians, bring the hand
        round the leaf's free edge to behind its far face, and push the leaf round the hinge
        to ``_PUSH_GOAL`` while the base backs away; (None, angle) once there, else why not.

        The hand comes in well behind where the robot believes the leaf is, and meets it on
        the way round wherever it truly stands: pushing needs no grip, only a face."""
        body = self.body
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0))
        hinge = door.hinge - _LEAF_HALF_THICKNESS * door.normal
        leaf = door.leaf_geometry(hinge)
        hand, grip = scene.grasp_frame(current_configuration(body))
        up = 1.0 if float(grip[2, 1]) > 0 else -1.0  # the fingers stay as they were
        height = float(to_odometry(_triple(body.odometry().pose), hand)[2])
        body.command_velocity(Twist())
        body.gripper().command(_HAND_OPEN)
        body.tick(max(1, round(0.4 / body.tick_period)))
        # off the lever, straight back, and turned to point along the leaf to the hinge
        back = hand - _DRAW_BACK * grip[:, 0]
        self._move_hand(scene, lambda f: (hand + f * (back - hand), grip), 0.8)
        body.gripper().command(0.0)
        pose = _triple(body.odometry().pose)
        self._move_hand(scene, lambda f: (back, _pushing_rotation(pose, leaf, believed, up)),
                        1.0)
        start = max(believed - _BEHIND, _PUSH_FROM - 0.2)
        outer = leaf.length + _EDGE_CLEAR
        inner = leaf.length - _IN_FROM_EDGE
        # the base steps along its heading to bring the leaf's edge within easy reach
        pose = _triple(body.odometry().pose)
        ahead = float(to_base(pose, leaf.point(outer, start, height))[0])
        self._step_base(ahead - _EDGE_AHEAD)
        # beyond the free edge on the robot's side, round it, and in behind the far face
        round_edge = np.linspace(believed + _FRONT, start, 4)
        path = [(outer, float(angle)) for angle in round_edge] + [(inner, start)]
        for (radius, angle), seconds in zip(path, (1.5, 0.8, 0.8, 0.8, 1.2), strict=True):
            here = scene.grasp_frame(current_configuration(body))[0]
            self._move_hand_to(scene, here, radius, angle, leaf, height, up, seconds)
        # round the hinge, pushing the far face wherever the leaf is met
        return self._sweep(scene, leaf, inner, start, height,
                           lambda pose, angle: _pushing_rotation(pose, leaf, angle, up),
                           lead=_PUSH_LEAD, goal=_PUSH_GOAL, backing=True)

    def _sweep(self, scene: PlanningScene, leaf: _Leaf, radius: float, start: float,
               height: float,
               rotation: Callable[[tuple[float, float, float], float], np.ndarray], *,
               lead: float, goal: float, backing: bool) -> tuple[str | None, float]:
        """Push the leaf's face round the hinge with the hand, ``radius`` from it, from
        ``start`` (radians round, where the hand stands clear of the face) to ``goal``;
        the target leads the hand by ``lead`` at most, so the hand presses on the face
        it meets and yields where the leaf holds. ``backing``: the base backs away to keep
        the hand ``_PUSH_AHEAD`` before it. (None, angle) once there, else why not."""
        body = self.body
        dt = body.tick_period
        began = body.now()
        commanded = angle = start
        while True:
            pose = _triple(body.odometry().pose)
            hand = scene.grasp_frame(current_configuration(body))[0]
            angle = leaf.angle_of(to_odometry(pose, hand)[:2])
            commanded = min(commanded + _PUSH_SPEED / radius * dt, angle + lead, goal)
            target = to_base(pose, leaf.point(radius, commanded, height))
            if backing:
                body.command_velocity(Twist(-min(_BASE_SPEED, max(0.0, _BASE_GAIN * (
                    _PUSH_AHEAD - float(target[0])))), 0.0, 0.0))
            self._step_towards(scene, target, rotation(pose, commanded))
            body.tick()
            if angle >= goal - 0.05:
                body.command_velocity(Twist())
                return None, angle
            if body.now() - began > _PUSH_LIMIT:
                body.command_velocity(Twist())
                return "the door took too long to open", angle

    def _push_away(self, door: _DoorInOdometry) -> tuple[str | None, float]:
        """Open a leaf that swings away from the robot, its lever pressed in the hand:
        push the lever a little round the hinge (the latch stays drawn once the leaf has
        left its frame), let go, step up to the doorway and push the leaf's near face
        round with the fingertips; (None, angle) once there, else why not."""
        body = self.body
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0))
        hinge = door.hinge - _LEAF_HALF_THICKNESS * door.normal
        leaf = door.leaf_geometry(hinge, away=True)
        pose = _triple(body.odometry().pose)
        hand, grip = scene.grasp_frame(current_configuration(body))
        at = to_odometry(pose, hand)
        radius = float(np.linalg.norm(at[:2] - leaf.hinge))
        first = leaf.angle_of(at[:2])  # the hand holds the lever before the face

        def nudged(f: float) -> tuple[np.ndarray, np.ndarray]:
            return to_base(pose, leaf.point(radius, first + f * _NUDGE, float(at[2]))), grip

        self._move_hand(scene, nudged, 1.2)
        moved = leaf.angle_of(to_odometry(_triple(body.odometry().pose), scene.grasp_frame(
            current_configuration(body))[0])[:2]) - first
        if moved < _NUDGE / 3:
            return "the door does not move: it may be locked", moved
        if body.gripper().state().width < _HOLDING:
            return "the handle slipped from my fingers", moved
        body.gripper().command(_HAND_OPEN)
        body.tick(max(1, round(0.4 / body.tick_period)))
        hand, grip = scene.grasp_frame(current_configuration(body))
        back = hand - _DRAW_BACK * grip[:, 0]
        self._move_hand(scene, lambda f: (hand + f * (back - hand), grip), 0.8)
        body.gripper().command(0.0)
        # up to the doorway: the base's middle _AWAY_STAND before the leaf's shut line
        pose = _triple(body.odometry().pose)
        self._step_base(float((np.array(pose[:2]) - door.hinge) @ door.normal) - _AWAY_STAND)
        up = 1.0 if float(grip[2, 1]) > 0 else -1.0
        start = moved - _AWAY_BEHIND
        height = float(at[2])
        here = scene.grasp_frame(current_configuration(body))[0]
        pose = _triple(body.odometry().pose)
        end = to_base(pose, leaf.point(_AWAY_RADIUS, start, height))
        towards = _into_face(pose, leaf, start, up)
        self._move_hand(scene, lambda f: (here + f * (end - here), towards), 1.5)
        return self._sweep(scene, leaf, _AWAY_RADIUS, start, height,
                           lambda pose, angle: _into_face(pose, leaf, angle, up),
                           lead=_AWAY_LEAD, goal=_AWAY_GOAL, backing=False)

    def _step_base(self, distance: float) -> None:
        """Drive the base ``distance`` along its heading (backwards if negative)."""
        body = self.body
        start = body.odometry().pose
        heading = np.array([math.cos(start.theta), math.sin(start.theta)])
        for _ in range(int(10.0 / body.tick_period)):
            done = float((np.array(body.odometry().pose.xy()) - start.xy()) @ heading)
            left = distance - done
            if abs(left) < 0.01:
                break
            body.command_velocity(Twist(math.copysign(min(0.15, 1.5 * abs(left)), left),
                                        0.0, 0.0))
            body.tick()
        body.command_velocity(Twist())
        body.tick()

    def _move_hand_to(self, scene: PlanningScene, start: np.ndarray, radius: float,
                      angle: float, leaf: _Leaf, height: float, up: float,
                      seconds: float) -> None:
        """Move the hand in a straight line (base frame, the base standing) from ``start``
        to ``radius`` from the hinge at ``angle`` round it, pointing towards the hinge."""
        pose = _triple(self.body.odometry().pose)
        end = to_base(pose, leaf.point(radius, angle, height))
        rotation = _pushing_rotation(pose, leaf, angle, up)
        self._move_hand(scene, lambda f: (start + f * (end - start), rotation), seconds)

    def _move_hand(self, scene: PlanningScene,
                   along: Callable[[float], tuple[np.ndarray, np.ndarray]],
                   seconds: float) -> None:
        """Step the hand along ``along`` (a fraction of the way: position and rotation, base
        frame) over ``seconds``, then let it settle."""
        ticks = max(1, round(seconds / self.body.tick_period))
        for k in range(1, ticks + 1):
            position, rotation = along(k / ticks)
            self._step_towards(scene, position, rotation)
            self.body.tick()
        for _ in range(max(1, round(0.3 / self.body.tick_period))):
            self._step_towards(scene, *along(1.0))
            self.body.tick()

    def _withdraw(self, door: _DoorInOdometry) -> None:
        """Draw the hand out from behind the leaf, past its edge, and tuck the arm."""
        body = self.body
        body.command_velocity(Twist())
        scene = PlanningScene(body.arm().description(), (0.0, 0.0, 0.0))
        hinge = door.hinge - _LEAF_HALF_THICKNESS * door.normal
        leaf = door.leaf_geometry(hinge)
        pose = _triple(body.odometry().pose)
        hand, rotation = scene.grasp_frame(current_configuration(body))
        at = to_odometry(pose, hand)
        angle = leaf.angle_of(at[:2])
        out = to_base(pose, leaf.point(leaf.length + _EDGE_CLEAR, angle - 0.1, float(at[2])))
        self._move_hand(scene, lambda f: (hand + f * (out - hand), rotation), 1.2)
        self._move_hand(scene, lambda f: (out + np.array([0.0, 0.0, _LIFT_OFF * f]), rotation),
                        0.8)
        follow(body, [current_configuration(body), TUCKED])

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
        local = to_base(_triple(here), np.array([point[0], point[1], 0.0]))
        if math.dist(here.xy(), point) > 0.03:
            if abs(float(local[1])) < _ALONG_ENOUGH:  # ahead or behind: no turning round
                self._step_base(float(local[0]))
            elif body.drive is DriveKind.OMNIDIRECTIONAL:
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

    def leaf_geometry(self, hinge: np.ndarray, *, away: bool = False) -> _Leaf:
        """The leaf turning round ``hinge`` (its axis, odometry frame), towards the robot
        or ``away`` from it."""
        along = self.latch - self.hinge
        length = float(np.linalg.norm(along))
        return _Leaf(hinge, along / length, -self.normal if away else self.normal, length)

    def leaf_obstacle(self, pose: tuple[float, float, float]) -> Obstacle:
        """The leaf as a box in the planning scene of a base at ``pose`` (odometry)."""
        middle = to_base(pose, np.array([*(self.hinge + self.latch) / 2, 1.0]))
        along = to_base(pose, np.array([*self.latch, 0.0]))[:2] - \
            to_base(pose, np.array([*self.hinge, 0.0]))[:2]
        width = float(np.linalg.norm(along))
        return Obstacle("door leaf", "box", (width, 0.04, 2.0),
                        (float(middle[0]), float(middle[1]), 1.0),
                        math.atan2(float(along[1]), float(along[0])))


@dataclass(frozen=True)
class _Leaf:
    """The leaf round its hinge (odometry frame): shut it points along ``along``; opening
    turns it towards ``normal`` (the robot's side)."""

    hinge: np.ndarray  #: (2,)
    along: np.ndarray  #: (2,) unit
    normal: np.ndarray  #: (2,) unit
    length: float

    def direction(self, angle: float) -> np.ndarray:
        """(2,) unit: from the hinge along the leaf opened by ``angle``."""
        return math.cos(angle) * self.along + math.sin(angle) * self.normal

    def point(self, radius: float, angle: float, height: float) -> np.ndarray:
        """(3,) the point ``radius`` from the hinge, ``angle`` round it, at ``height``."""
        return np.array([*(self.hinge + radius * self.direction(angle)), height])

    def face_normal(self, angle: float) -> np.ndarray:
        """(2,) unit: the outward normal of the face that leads the way round (the one a
        hand pushes to open the leaf further)."""
        return math.sin(angle) * self.along - math.cos(angle) * self.normal

    def angle_of(self, point: np.ndarray) -> float:
        """How far round the hinge, from shut, the (2,) ``point`` lies."""
        offset = point - self.hinge
        return math.atan2(float(offset @ self.normal), float(offset @ self.along))


def _pushing_rotation(pose: tuple[float, float, float], leaf: _Leaf, angle: float,
                      up: float) -> np.ndarray:
    """The pushing hand's rotation (base frame): pointing along the leaf towards the
    hinge, so the wrist stays out past the free edge and the hand's flat side meets the
    leaf's face; turned ``_HAND_TILT`` off the face, so the forearm comes round the
    edge from the robot's side without crossing the leaf."""
    towards = -math.cos(_HAND_TILT) * leaf.direction(angle) + \
        math.sin(_HAND_TILT) * leaf.face_normal(angle)
    local = to_base(pose, np.array([*towards, 0.0])) - to_base(pose, np.zeros(3))
    return _grasp_rotation(local[:2], up)


def _into_face(pose: tuple[float, float, float], leaf: _Leaf, angle: float,
               up: float) -> np.ndarray:
    """The hand's rotation (base frame) pointing into the leaf's face that leads the way
    round (the one the hand pushes), the leaf opened by ``angle``."""
    local = to_base(pose, np.array([*(-leaf.face_normal(angle)), 0.0])) - \
        to_base(pose, np.zeros(3))
    return _grasp_rotation(local[:2], up)


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
