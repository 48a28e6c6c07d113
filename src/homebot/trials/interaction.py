"""Physical interaction trials in MuJoCo: handover, receiving, guiding, carrying a table, a door.

The scenarios ``handover``, ``receive``, ``guided_by_hand``, ``carry_table`` and
``open_door`` run one episode each; ``homebot bench manipulation`` runs many and prints
their figures. Every episode runs the robot's behaviour
(``homebot.manipulation.interaction``) on the compliance controller in an
``InteractionScene``; the person is a seeded force profile or a gripping hand
(``homebot.sim.forces``). The robot's side reads what its drivers report (the arm's
joints, the hand's pose and Jacobian, the wrist's force-torque sensor, the torso's
height, the base's odometry) and its torso laser (``InteractionScene.laser``): the
carried table's pitch is fitted to the laser's points on its top
(``homebot.perception.table_pitch``). The door's leaf, hinge and handle are found in the
head camera's depth points (``InteractionScene.camera``, ``homebot.perception.door_leaf``)
from before the doorway; nothing of the door's truth reaches the robot. Success is judged
on the physics' ground truth: when the bottle truly left the fingers, where the robot's
base truly went, how level the table truly was, how far the door's hinge truly turned.
"""

from __future__ import annotations

import itertools
import math
import statistics
from dataclasses import dataclass
from typing import Any

import numpy as np

from homebot.manipulation.compliance import ArmReading, Compliance, ComplianceController
from homebot.manipulation.interaction import (
    CarryPhase,
    CarryTable,
    Command,
    GuidedByHand,
    Handover,
    Receive,
    ReceivePhase,
)
from homebot.perception.table_pitch import TablePitch
from homebot.robot import DriveKind, HeadState, Twist
from homebot.sim.forces import GrippingHand, Trajectory, apply_at, handover_trial
from homebot.sim.hri import InteractionScene

__all__ = [
    "DOOR_OPEN",
    "DOOR_SHUT",
    "HANDOVER_THRESHOLD",
    "BaseDrive",
    "CarryProfile",
    "CarryResult",
    "DoorResult",
    "DoorVariant",
    "GuidedResult",
    "HandoverResult",
    "ReceiveResult",
    "apply",
    "carry_profile",
    "carry_table_episode",
    "door_episode",
    "door_scene",
    "door_variant",
    "drive_base",
    "guided_episode",
    "guided_route",
    "handover_episode",
    "reach",
    "reading",
    "receive_episode",
]

HANDOVER_THRESHOLD = 10.0  #: newtons: a pull above this is the person taking the object
RELEASE_DEADLINE = 0.5  #: seconds from the pull's crossing the threshold to the release
#: The arm held out in front, hand level at about 1 m (torso lifted 0.1 m).
HOLD_OUT = np.array([0.0, 0.5, 0.0, -1.2, 0.0, 0.7, 0.0])
_TORSO = 0.1
_BOTTLE_GRIP = 0.035  #: finger travel that just touches the 3 cm bottle
_OPEN = 0.07
_RNG_STREAM = 1818
_OMNI = DriveKind.OMNIDIRECTIONAL


def reading(scene: InteractionScene) -> ArmReading:
    """What the arm's drivers report now."""
    return ArmReading(*scene.arm_state())


def apply(scene: InteractionScene, controller: ComplianceController, command: Command) -> None:
    """Send one tick's command: compliance target, gripper, torso (not the base)."""
    controller.target_position = command.hand_position
    controller.target_rotation = command.hand_rotation
    controller.compliance = command.compliance
    scene.command_torques(controller.torques(reading(scene)))
    scene.grip(command.gripper_closed)
    if command.torso is not None:
        scene.lift_torso(command.torso)


class BaseDrive:
    """The kinematic base under velocity commands, as a base's motor controller takes them:
    clipped to the velocity limits and reached within the acceleration limits (m/s²,
    rad/s²), so a sudden command does not jerk the arm and what it holds."""

    def __init__(self, scene: InteractionScene, *, speed: float = 0.7, turn: float = 1.2,
                 acceleration: float = 1.0, angular_acceleration: float = 2.5) -> None:
        from homebot.robot import VelocityLimits

        self.scene = scene
        self.limits = VelocityLimits(speed, turn, acceleration, angular_acceleration)
        self.velocity = Twist()

    def drive(self, command: Twist, dt: float) -> None:
        """Move for ``dt`` seconds towards the commanded base-frame twist."""
        wanted = self.limits.clip(command, _OMNI)
        now = self.velocity
        step = self.limits.linear_acceleration * dt
        dvx, dvy = wanted.vx - now.vx, wanted.vy - now.vy
        change = math.hypot(dvx, dvy)
        if change > step:
            dvx, dvy = dvx * step / change, dvy * step / change
        turn = self.limits.angular_acceleration * dt
        dwz = max(-turn, min(turn, wanted.wz - now.wz))
        self.velocity = Twist(now.vx + dvx, now.vy + dvy, now.wz + dwz)
        drive_base(self.scene, self.velocity, dt)


def drive_base(scene: InteractionScene, twist: Twist, dt: float) -> None:
    """Drive the kinematic base at a base-frame twist (over the next ``dt`` seconds of
    physics: the scene keeps the velocity until the next command)."""
    del dt
    _, _, theta = scene.base_pose()
    c, s = math.cos(theta), math.sin(theta)
    scene.drive_base(c * twist.vx - s * twist.vy, s * twist.vx + c * twist.vy, twist.wz)


def _holding_scene(scene_name: str = "handover") -> tuple[InteractionScene,
                                                           ComplianceController]:
    scene = InteractionScene(scene_name)
    scene.set_arm(HOLD_OUT, torso=_TORSO, gripper=_BOTTLE_GRIP)
    scene.place_body("object", scene.hand_world())
    scene.grip(True)
    start = reading(scene)
    controller = ComplianceController(Compliance(), start.hand_position,
                                      start.hand_rotation, rest=HOLD_OUT)
    return scene, controller


def _in_hand(scene: InteractionScene) -> bool:
    """Ground truth: a finger touches the bottle."""
    return scene.touching("object", "left_pad") or scene.touching("object", "right_pad")


# ------------------------------------------------------------------ handover


@dataclass(frozen=True)
class HandoverResult:
    """One handover trial, judged by the physics."""

    pull_above: float | None  #: when the person's pull exceeded the threshold (None: no pull)
    decided_at: float | None  #: when the robot opened its hand
    left_hand_at: float | None  #: when the bottle truly left the fingers
    bumps: int
    seconds: float = 0.0  #: simulated

    @property
    def delay(self) -> float | None:
        if self.pull_above is None or self.left_hand_at is None:
            return None
        return self.left_hand_at - self.pull_above

    @property
    def correct(self) -> bool:
        if self.pull_above is None:
            return self.left_hand_at is None
        delay = self.delay
        return delay is not None and 0.0 <= delay <= RELEASE_DEADLINE


def handover_episode(seed: int, index: int, *, pull: bool | None = None,
                     threshold: float = HANDOVER_THRESHOLD) -> HandoverResult:
    """Trial ``index`` of ``seed``: the robot holds the bottle out; the person bumps it and
    perhaps pulls (``pull``: force the choice; None draws it, 80 % pull)."""
    rng = np.random.default_rng([seed, _RNG_STREAM, index])
    trial = handover_trial(rng, threshold=threshold, pull=pull)
    scene, controller = _holding_scene()
    start = reading(scene)
    behaviour = Handover(start.hand_position, start.hand_rotation, threshold=threshold)
    bottle = scene.body_id("object")
    settle = 0.3  # the grip settles before the person comes

    def person(s: InteractionScene, t: float) -> None:
        if s.data.time >= settle:
            apply_at(s.model, s.data, bottle, s.body_position("object"),
                     trial.profile.at(t - settle))

    scene.pushers.append(person)
    left: float | None = None
    while scene.time < settle + trial.duration:
        apply(scene, controller, behaviour.update(scene.time - settle, controller.shift))
        scene.step()
        if left is None and scene.time > settle and not _in_hand(scene):
            left = scene.time - settle
    return HandoverResult(trial.pull_above, behaviour.released_at, left, trial.bumps, scene.time)


# ------------------------------------------------------------------ guided by the hand

GUIDE_SPEED = 0.5  #: m/s the person walks
_CLEARANCE = 0.5  #: metres the person's route keeps from walls and furniture
_HAND_REACH = 1.0  #: metres from the base's centre to the held-out hand, at most


@dataclass(frozen=True)
class GuidedResult:
    """One guided walk, judged by the physics and the world's geometry."""

    route_length: float
    deviations: tuple[float, ...]  #: the base's distance from the person's path, per tick
    hand_deviations: tuple[float, ...]  #: the hand's distance from the person's path
    collisions: int  #: ticks the base's footprint overlapped a wall or furniture
    arrived: bool  #: the robot's hand ended within 0.5 m of the person's
    seconds: float = 0.0  #: simulated

    @property
    def median_deviation(self) -> float:
        return statistics.median(self.deviations) if self.deviations else math.inf


def _distance_to_path(point: np.ndarray, path: np.ndarray) -> float:
    a, b = path[:-1], path[1:]
    ab = b - a
    length = np.einsum("ij,ij->i", ab, ab)
    t = np.clip(np.einsum("ij,ij->i", point - a, ab) / np.where(length > 0, length, 1.0), 0, 1)
    nearest = a + t[:, None] * ab
    return float(np.min(np.linalg.norm(nearest - point, axis=1)))


def guided_route(seed: int, index: int) -> tuple[tuple[float, float], ...]:
    """A seeded walk through the apartment: from a free start (with room behind it for
    the robot) to a free goal 3–8 m away, keeping ``_CLEARANCE`` from walls and furniture."""
    from homebot.navigation import Navigator
    from homebot.world import DoorState, World

    world = World.load("apartment")
    navigator = _navigator(world, Navigator)
    closed = frozenset(name for name, door in world.doors.items()
                       if door.state is not DoorState.OPEN)
    rng = np.random.default_rng([seed, _RNG_STREAM, 2, index])
    (x0, x1), (y0, y1) = _bounds(world)
    for _ in range(5000):
        start = (float(rng.uniform(x0, x1)), float(rng.uniform(y0, y1)))
        goal = (float(rng.uniform(x0, x1)), float(rng.uniform(y0, y1)))
        if not 3.0 <= math.dist(start, goal) <= 8.0:
            continue
        if world.footprint_problem(*start, radius=_CLEARANCE) or \
                world.footprint_problem(*goal, radius=_CLEARANCE):
            continue
        path = navigator.plan_around(start, goal, closed, np.empty((0, 2)), 0.0,
                                     static_clearance=_CLEARANCE)
        if path is None or len(path) < 2:
            continue
        heading = _start_heading(path)
        behind = [(start[0] - f * _HAND_REACH * math.cos(heading),
                   start[1] - f * _HAND_REACH * math.sin(heading)) for f in (0.5, 0.75, 1.0)]
        if any(world.footprint_problem(*point, radius=world.model.robot.radius + 0.05)
               for point in behind):
            continue
        return tuple((float(p[0]), float(p[1])) for p in path)
    raise RuntimeError("no guided route found in the apartment")  # the map is broken


def _start_heading(path: Any) -> float:
    """The way the route leaves its start: towards its first point half a metre away (a
    planner's first waypoint may be a few centimetres off to a side)."""
    x0, y0 = path[0]
    for x, y in path[1:]:
        if math.dist((x0, y0), (x, y)) >= 0.5:
            return math.atan2(y - y0, x - x0)
    return math.atan2(path[-1][1] - y0, path[-1][0] - x0)


_NAVIGATORS: dict[int, Any] = {}


def _navigator(world: Any, navigator_class: Any) -> Any:
    """One Navigator per process for the apartment (its grid takes a while to build)."""
    key = id(navigator_class)
    if key not in _NAVIGATORS:
        _NAVIGATORS[key] = navigator_class(world)
    return _NAVIGATORS[key]


def _bounds(world: Any) -> tuple[tuple[float, float], tuple[float, float]]:
    from shapely.ops import unary_union

    x0, y0, x1, y1 = unary_union(list(world.room_polygons.values())).bounds
    return (x0, x1), (y0, y1)


def guided_episode(seed: int, index: int) -> GuidedResult:
    """Route ``index`` of ``seed``: a person takes the robot's hand and walks the route."""
    from homebot.world import World

    world = World.load("apartment")
    route = guided_route(seed, index)
    scene = InteractionScene("guide")
    scene.set_arm(HOLD_OUT, torso=_TORSO, gripper=0.0)
    heading = _start_heading(route)
    hand_local = reading(scene).hand_position
    c, s = math.cos(heading), math.sin(heading)
    scene.move_base(route[0][0] - c * hand_local[0] + s * hand_local[1],
                    route[0][1] - s * hand_local[0] - c * hand_local[1], heading)
    scene.step()
    start = reading(scene)
    controller = ComplianceController(Compliance(), start.hand_position, start.hand_rotation,
                                      rest=HOLD_OUT)
    behaviour = GuidedByHand(start.hand_position, start.hand_rotation)
    height = float(scene.hand_world()[2])
    walk = Trajectory.walked([(x, y, height) for x, y in route], GUIDE_SPEED, start=0.5)
    person = GrippingHand(walk)
    gripper = scene.body_id("gripper")

    def lead(sc: InteractionScene, t: float) -> None:
        point = sc.hand_world()
        apply_at(sc.model, sc.data, gripper, point,
                 person.force(t, point, sc.body_velocity("gripper", point)))

    scene.pushers.append(lead)
    # The person's path, from where the robot stood when they took its hand.
    path = np.asarray([scene.base_pose()[:2], *route])
    deviations, hand_deviations, collisions = [], [], 0
    radius = world.model.robot.radius
    base = BaseDrive(scene, speed=max(0.7, world.model.robot.speed),
                     turn=world.model.robot.angular_speed)
    while scene.time < walk.end + 4.0:
        command = behaviour.update(controller.shift, scene.base_pose())
        apply(scene, controller, command)
        scene.step()
        base.drive(command.base, scene.control_period)
        x, y, _ = scene.base_pose()
        if scene.time > walk.times[0]:
            deviations.append(_distance_to_path(np.array([x, y]), path))
            hand_deviations.append(_distance_to_path(scene.hand_world()[:2], path))
        if world.footprint_problem(x, y, radius=radius) is not None:
            collisions += 1
    arrived = float(np.linalg.norm(scene.hand_world()[:2] - path[-1])) < 0.5
    length = float(sum(math.dist(a, b) for a, b in itertools.pairwise(route)))
    return GuidedResult(length, tuple(deviations), tuple(hand_deviations), collisions, arrived,
                        scene.time)


# ------------------------------------------------------------------ carrying a table

LEVEL_LIMIT = math.radians(3.0)  #: the table must stay this level while carried
_HANDLE_HEIGHT = 0.76  #: the upright handle's centre above the floor
_HANDLE_OFFSET = 0.64  #: from the table's centre to its handle, along the table
_TABLE_LENGTH = 1.2
_LEG_GAP = 0.005  #: the table's legs end this far below its frame's floor level


def reach(scene: InteractionScene, position: np.ndarray, rotation: np.ndarray,
          q: np.ndarray, *, iterations: int = 200) -> np.ndarray:
    """Joint angles that put the hand at a pose (base frame), by damped least squares
    from ``q``; the scene's arm is left there."""
    from scipy.spatial.transform import Rotation

    q = np.asarray(q, dtype=float).copy()
    for _ in range(iterations):
        scene.set_arm(q)
        now = reading(scene)
        error = np.concatenate((position - now.hand_position, Rotation.from_matrix(
            rotation @ now.hand_rotation.T).as_rotvec()))
        if float(np.linalg.norm(error)) < 1e-6:
            break
        jacobian = now.jacobian
        q = q + jacobian.T @ np.linalg.solve(jacobian @ jacobian.T + 1e-4 * np.eye(6), error)
    scene.set_arm(q)
    return q


@dataclass(frozen=True)
class CarryResult:
    """One carry, judged by the table's true pose."""

    lifted_at: float | None  #: seconds after the person began lifting that the robot did
    lowered: bool  #: the robot ended with the table down (phase done, table on its legs)
    max_tilt_deg: float  #: worst tilt of the table top while it was off the floor
    max_height: float  #: how high the table was carried (m)
    travelled: float  #: how far the table's centre moved on the floor (m)
    dropped: bool  #: the robot's fingers lost the table
    seconds: float = 0.0  #: simulated
    #: the largest gap between the pitch the robot perceived and the table's true pitch
    #: while the table was off the floor (degrees)
    pitch_error_deg: float = 0.0

    @property
    def success(self) -> bool:
        return (self.lowered and not self.dropped and self.max_tilt_deg <= math.degrees(
            LEVEL_LIMIT) and self.max_height > 0.1 and self.travelled > 1.0)


@dataclass(frozen=True)
class CarryProfile:
    """What one person does with their end of the table (ground truth, drawn per seed)."""

    lift: float  #: metres the person raises their end
    lift_time: float  #: seconds the lift (and the lowering) takes
    distance: float  #: metres walked with the table
    heading: float  #: walking direction, world frame: 0 away from the robot, pi towards it
    speed: float  #: m/s walking


def carry_profile(rng: np.random.Generator) -> CarryProfile:
    """A seeded person: lifts 0.15-0.4 m in 0.6-1.5 s, walks 1.2-3 m at 0.2-0.45 m/s, in
    three of four carries away from the robot (up to 25 deg to either side, the robot
    pulled), else towards it (up to 15 deg off, the robot pushed back), and lowers."""
    lift = float(rng.uniform(0.15, 0.4))
    lift_time = float(rng.uniform(0.6, 1.5))
    distance = float(rng.uniform(1.2, 3.0))
    away = bool(rng.random() < 0.75)
    heading = float(rng.uniform(-0.44, 0.44)) if away else \
        math.pi + float(rng.uniform(-0.26, 0.26))
    speed = float(rng.uniform(0.2, 0.45))
    return CarryProfile(lift, lift_time, distance, heading, speed)


def carry_table_episode(seed: int, index: int = 0) -> CarryResult:
    """A person lifts the far end of the table, walks with it and lowers it
    (``carry_profile``)."""
    rng = np.random.default_rng([seed, _RNG_STREAM, 3, index])
    profile = carry_profile(rng)
    scene = InteractionScene("table", sensor_seed=int(rng.integers(2**31)))
    q = reach(scene, np.array([0.72, 0.0, _HANDLE_HEIGHT]), np.eye(3),
              np.array([0.0, 1.2, 0.0, -1.9, 0.0, 0.7, 0.0]))
    scene.set_arm(q, torso=0.0, gripper=0.07)
    hand = scene.hand_world()
    scene.place_body("table", [hand[0] + _HANDLE_OFFSET, hand[1], -_LEG_GAP])
    controller, start = _close_fingers(scene, q, steps=30)  # on the table's edge
    behaviour = CarryTable(start.hand_position, start.hand_rotation,
                           length=_TABLE_LENGTH + _HANDLE_OFFSET - _TABLE_LENGTH / 2,
                           torso=scene.torso_height())
    far = scene.model.site("far_edge").id
    table = scene.body_id("table")
    here = np.asarray(scene.data.site_xpos[far], dtype=float).copy()
    lift, lift_time = profile.lift, profile.lift_time
    t0 = scene.time + 1.0
    up = here + np.array([0.0, 0.0, lift])
    away = up + profile.distance * np.array([math.cos(profile.heading),
                                             math.sin(profile.heading), 0.0])
    down = away - np.array([0.0, 0.0, lift])
    walk = _eased(up, away, profile.speed)  # a person speeds up and slows down over 0.6 s
    lifted = t0 + lift_time + 0.5
    walked = lifted + walk[-1][0]
    times = (t0, t0 + lift_time, *(lifted + dt for dt, _ in walk), walked + 1.0,
             walked + 1.0 + lift_time)
    points = (here, up, *(p for _, p in walk), away, down)
    person = GrippingHand(Trajectory(times, tuple((float(p[0]), float(p[1]), float(p[2]))
                                                  for p in points)),
                          stiffness=2000.0, damping=150.0, max_force=150.0)

    def hold(sc: InteractionScene, t: float) -> None:
        point = np.asarray(sc.data.site_xpos[far], dtype=float)
        apply_at(sc.model, sc.data, table, point,
                 person.force(t, point, sc.body_velocity("table", point)))

    scene.pushers.append(hold)
    start_xy = scene.body_position("table")[:2]
    floor_height = scene.body_position("table")[2]
    max_tilt, max_height, lifted_at, dropped, pitch_error = 0.0, 0.0, None, False, 0.0
    base = BaseDrive(scene)
    tracker = TablePitch()
    while scene.time < times[-1] + 4.0 and behaviour.phase is not CarryPhase.DONE:
        _scan_table(scene, tracker)  # a scan every control tick (100 Hz)
        command = behaviour.update(scene.control_period, controller.shift, tracker.pitch)
        if lifted_at is None and behaviour.phase is CarryPhase.CARRYING:
            lifted_at = scene.time - t0
        apply(scene, controller, command)
        scene.step()
        base.drive(command.base, scene.control_period)
        height = scene.body_position("table")[2] - floor_height
        max_height = max(max_height, height)
        if height > 0.02:  # off the floor: it must be level
            top = scene.body_rotation("table")
            max_tilt = max(max_tilt, math.degrees(math.acos(min(1.0, abs(top[2, 2])))))
            pitch_error = max(pitch_error, abs(math.degrees(tracker.pitch - _true_pitch(scene))))
        if float(np.linalg.norm(scene.hand_world() - np.asarray(
                scene.data.geom("handle").xpos))) > 0.08:
            dropped = True  # the handle is out of the fingers
    for _ in range(100):  # the table settles
        scene.step()
    travelled = float(np.linalg.norm(scene.body_position("table")[:2] - start_xy))
    down_now = scene.body_position("table")[2] - floor_height < 0.02
    return CarryResult(lifted_at, bool(behaviour.phase is CarryPhase.DONE and down_now),
                       round(max_tilt, 3), round(float(max_height), 3), round(travelled, 3),
                       dropped, scene.time, round(pitch_error, 3))


def _eased(a: np.ndarray, b: np.ndarray, speed: float,
           ease: float = 0.6) -> list[tuple[float, np.ndarray]]:
    """(time, point) from ``a`` to ``b`` at ``speed``, speeding up over the first ``ease``
    seconds and slowing down over the last (in thirds of the speed)."""
    length = float(np.linalg.norm(b - a))
    step = ease / 3
    ramp = [speed * k / 3 * step for k in (1, 2)]  # distance covered at 1/3 and 2/3 speed
    if length < 2 * sum(ramp):
        return [(0.0, a), (length / speed * 2, b)]
    direction = (b - a) / length
    marks = [0.0, ramp[0], ramp[0] + ramp[1], length - ramp[0] - ramp[1], length - ramp[0], length]
    speeds = [speed / 3, 2 * speed / 3, speed, 2 * speed / 3, speed / 3]
    out, t = [(0.0, a)], 0.0
    for (m0, m1), v in zip(itertools.pairwise(marks), speeds, strict=True):
        t += (m1 - m0) / v
        out.append((t, a + m1 * direction))
    return out


def _true_pitch(scene: InteractionScene) -> float:
    """Ground truth for the referee: the table's pitch (positive: the person's end higher)."""
    near = np.asarray(scene.data.site("near_edge").xpos)
    far = np.asarray(scene.data.site("far_edge").xpos)
    run = float(np.linalg.norm((far - near)[:2]))
    return math.atan2(float(far[2] - near[2]), run)


def _scan_table(scene: InteractionScene, tracker: TablePitch) -> float:
    """One laser scan over the carried table, and the pitch the tracker makes of it."""
    arm = reading(scene)
    torso = scene.torso_height()
    ranges = scene.laser(tracker.mount(torso), tracker.directions(arm.hand_rotation))
    return tracker.update(torso, arm.hand_position, arm.hand_rotation, ranges)


# ------------------------------------------------------------------ receiving


@dataclass(frozen=True)
class ReceiveResult:
    """One hand-over from a person to the robot, judged by the physics."""

    phase: str  #: where the robot's behaviour ended (``holding`` when it believes it has it)
    closed_at: float | None  #: when the robot closed its hand
    let_go_at: float | None  #: when the person let go
    held: bool  #: truth: at the end both fingers touch the bottle and it hangs in the hand

    @property
    def success(self) -> bool:
        return self.held and self.phase == ReceivePhase.HOLDING.value


def receive_episode(seed: int, index: int = 0) -> ReceiveResult:
    """A person brings the bottle to the robot's open hand (from 0.25–0.45 m in front, at
    a seeded height and sideways offset within the fingers' reach), pushes it in until it
    touches the palm, and lets go once the fingers hold it."""
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng([seed, _RNG_STREAM, 4, index])
    scene = InteractionScene("handover")
    scene.set_arm(HOLD_OUT, torso=_TORSO, gripper=_OPEN)
    scene.grip(False)
    hand = scene.hand_world()
    start_point = hand + np.array([rng.uniform(0.25, 0.45), rng.uniform(-0.1, 0.1),
                                   rng.uniform(-0.05, 0.1)])
    inside = hand + np.array([-0.045, rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01)])
    scene.place_body("object", start_point)
    arrive = 0.5 + math.dist(start_point, inside) / 0.3
    person = GrippingHand(Trajectory((0.5, arrive), (tuple(start_point), tuple(inside))),
                          stiffness=800.0, damping=60.0, max_force=40.0)
    bottle = scene.body_id("object")
    state: dict[str, float | None] = {"both_since": None, "let_go": None}

    def give(sc: InteractionScene, t: float) -> None:
        if state["let_go"] is not None:
            return
        point = sc.body_position("object")
        velocity = sc.body_velocity("object", point)
        apply_at(sc.model, sc.data, bottle, point, person.force(t, point, velocity))
        turn = Rotation.from_matrix(sc.body_rotation("object")).as_rotvec()
        spin = sc.data.cvel[bottle][:3]
        sc.data.xfrc_applied[bottle, 3:] += -0.3 * turn - 0.004 * spin  # the wrist keeps it up

    scene.pushers.append(give)
    start = reading(scene)
    controller = ComplianceController(Compliance(), start.hand_position, start.hand_rotation,
                                      rest=HOLD_OUT)
    behaviour = Receive(start.hand_position, start.hand_rotation)
    end = arrive + 6.0
    while scene.time < end:
        command = behaviour.update(scene.time, scene.wrist_wrench()[:3], scene.gripper_opening())
        apply(scene, controller, command)
        scene.step()
        both = scene.touching("object", "left_pad") and scene.touching("object", "right_pad")
        if state["let_go"] is None:
            if both and state["both_since"] is None:
                state["both_since"] = scene.time
            elif not both:
                state["both_since"] = None
            since = state["both_since"]
            if since is not None and scene.time - since > 0.3:
                state["let_go"] = scene.time
                end = min(end, scene.time + 2.0)
    held = bool(_in_hand(scene) and scene.touching("object", "left_pad") and scene.touching(
        "object", "right_pad") and abs(scene.body_position("object")[2] - scene.hand_world()[2])
        < 0.06)  # a plain bool: the scenario prints it as JSON
    return ReceiveResult(behaviour.phase.value, behaviour.closed_at, state["let_go"], held)


# ------------------------------------------------------------------ opening and closing a door

DOOR_OPEN = math.radians(60.0)  #: the door must truly open at least this far
DOOR_SHUT = math.radians(2.0)  #: and be truly within this of its frame when closed
_DOOR_HANDLE_HEIGHT = 0.95
_DOOR_HANDLE_STANDOFF = 0.08  #: from the hinge axis towards the robot to the bar's axis
_DOOR_HANDLE_INSET = 0.08  #: from the free edge to the bar
_DOOR_X = 0.8  #: the hinge axis before the robot's start
_DOOR_TORSO = 0.2
_DOOR_LOOK = 1.2  #: metres before the doorway where the robot stands to look at the door
_DOOR_TILT = 0.2  #: radians the head looks down at the door
_BAR_HALF = 0.015  #: metres: half a handle bar's thickness
_DOOR_TUCKED = (0.0, -1.4, 0.0, -1.8, 0.0, -1.3, 0.0)  #: the arm out of the camera's view


@dataclass(frozen=True)
class DoorVariant:
    """One door (ground truth)."""

    side: str  #: "left" or "right": where the hinge is, as the robot faces the door
    width: float  #: m
    friction: float  #: the hinge's dry friction (N·m)
    damping: float  #: the hinge's damping (N·m·s/rad)

    @property
    def sign(self) -> float:
        return 1.0 if self.side == "left" else -1.0

    @property
    def hinge(self) -> tuple[float, float]:
        """The hinge axis in the scene (world frame)."""
        return _DOOR_X, self.sign * self.width / 2

    @property
    def handle(self) -> np.ndarray:
        """The handle's centre in the scene with the door shut."""
        x, y = self.hinge
        return np.array([x - _DOOR_HANDLE_STANDOFF,
                         y - self.sign * (self.width - _DOOR_HANDLE_INSET),
                         _DOOR_HANDLE_HEIGHT])


def door_variant(rng: np.random.Generator) -> DoorVariant:
    """A seeded door: hinged left or right, 0.7–0.95 m wide, 0.3–3 N·m of hinge friction
    and 0.5–5 N·m·s/rad of damping."""
    return DoorVariant("left" if rng.random() < 0.5 else "right",
                       float(rng.uniform(0.7, 0.95)), float(rng.uniform(0.3, 3.0)),
                       float(rng.uniform(0.5, 5.0)))


def door_scene(variant: DoorVariant) -> InteractionScene:
    """The door scene (``homebot/sim/mjcf/door.xml``) changed to ``variant``."""

    def edit(spec: Any) -> None:
        sign, width = variant.sign, variant.width
        door = spec.body("door")
        door.pos = [_DOOR_X, sign * width / 2, 0.0]
        hinge = spec.joint("hinge")
        hinge.range = [-1.9, 0.0] if sign > 0 else [0.0, 1.9]
        hinge.frictionloss = variant.friction
        if np.ndim(hinge.damping):  # MuJoCo 4 has a damping polynomial
            damping = np.zeros(np.shape(hinge.damping))
            damping[0] = variant.damping
            hinge.damping = damping
        else:
            hinge.damping = variant.damping
        leaf = spec.geom("leaf")
        leaf.size = [0.02, width / 2 - 0.005, 1.0]
        leaf.pos = [0.0, -sign * width / 2, 1.01]
        across = -sign * (width - _DOOR_HANDLE_INSET)
        for name in ("handle", "handle_top", "handle_bottom"):
            geom = spec.geom(name)
            geom.pos = [geom.pos[0], across, geom.pos[2]]
        site = spec.site("handle_centre")
        site.pos = [site.pos[0], across, site.pos[2]]
        for name, side in (("jamb_left", 1.0), ("jamb_right", -1.0)):
            jamb = spec.geom(name)
            jamb.pos = [jamb.pos[0], side * (width / 2 + 0.06), jamb.pos[2]]

    return InteractionScene("door", edit=edit)


@dataclass(frozen=True)
class DoorResult:
    """One door opened and closed, judged by the hinge's true angle."""

    variant: DoorVariant
    opened_deg: float  #: the largest true opening
    closed_deg: float  #: the true angle at the end (after the robot let go)
    lost_handle: bool  #: the handle left the fingers at some point
    open_s: float | None  #: seconds to open (None: never reported open)
    close_s: float | None  #: seconds to close (None: never reported closed)
    worst_force: float  #: the largest planar force the hand exerted (N)
    bumped: int = 0  #: ticks the robot's body or arm (not its hand) touched the door or frame
    seconds: float = 0.0  #: simulated
    #: metres between the hinge the camera found and the true hinge axis (None: no door
    #: with a handle was seen, and the robot did not try)
    hinge_error: float | None = None
    #: metres between the handle the camera found and the true bar's centre
    handle_error: float | None = None

    @property
    def perceived(self) -> bool:
        return self.hinge_error is not None

    @property
    def success(self) -> bool:
        return (self.perceived and self.opened_deg >= math.degrees(DOOR_OPEN) and
                abs(self.closed_deg) <= math.degrees(DOOR_SHUT) and not self.lost_handle and
                self.open_s is not None and self.close_s is not None and not self.bumped)


def _bumped(scene: InteractionScene, body: set[int], door: set[int]) -> bool:
    data = scene.data
    for k in range(data.ncon):
        a, b = int(data.contact[k].geom1), int(data.contact[k].geom2)
        if (a in body and b in door) or (b in body and a in door):
            return True
    return False


def _perceive_door(scene: InteractionScene, seed: int, index: int
                   ) -> tuple[np.ndarray, np.ndarray] | None:
    """The door's hinge (x, y) and handle (x, y, z) as the head camera sees them from
    ``_DOOR_LOOK`` metres before the doorway's middle (scene frame: where the robot's
    odometry puts them), or None when no door with a handle is seen; the robot stands
    there after."""
    from homebot.perception.door_leaf import perceive_door

    scene.move_base(_DOOR_X - _DOOR_LOOK, 0.0, 0.0)
    frame = scene.camera(HeadState(0.0, _DOOR_TILT))
    seen = perceive_door(frame.points()[0],
                         np.random.default_rng([seed, _RNG_STREAM, 6, index]))
    if seen is None:
        return None
    hinge = scene.to_world(np.array([*seen.hinge, 0.0]))[:2]
    # The camera sees the handle's face; the fingers close round its middle, a bar's
    # half-thickness behind it.
    handle = scene.to_world(seen.handle - _BAR_HALF * np.array([*seen.normal, 0.0]))
    return hinge, handle


def door_episode(seed: int, index: int = 0, *, variant: DoorVariant | None = None,
                 time_limit: float = 25.0) -> DoorResult:
    """The robot looks at a seeded door, finds its leaf, handle and hinge in the head
    camera's depth points (``homebot.perception.door_leaf``), grasps the handle it saw,
    opens the door round the hinge it saw, then closes it."""
    from homebot.manipulation.interaction import DoorMotion, DoorPhase

    rng = np.random.default_rng([seed, _RNG_STREAM, 5, index])
    door = variant if variant is not None else door_variant(rng)
    scene = door_scene(door)
    scene.set_arm(np.array(_DOOR_TUCKED), torso=_DOOR_TORSO, gripper=_OPEN)
    found = _perceive_door(scene, seed, index)
    if found is None:
        return DoorResult(door, 0.0, 0.0, False, None, None, 0.0, seconds=scene.time)
    hinge, handle = found
    hinge_error = float(np.linalg.norm(hinge - np.asarray(door.hinge)))
    handle_error = float(np.linalg.norm(handle - door.handle))
    scene.move_base(0.0, float(handle[1]), 0.0)
    seen = scene.to_base(handle)
    scene.set_arm(np.array([0.0, 1.2, 0.0, -1.9, 0.0, 0.7, 0.0]), torso=_DOOR_TORSO,
                  gripper=_OPEN)
    q = reach(scene, seen, np.eye(3), np.array([0.0, 1.2, 0.0, -1.9, 0.0, 0.7, 0.0]))
    scene.set_arm(q, torso=_DOOR_TORSO, gripper=_OPEN)
    controller, start = _close_fingers(scene, q, steps=40)  # on the door's bar
    behaviour = DoorMotion((float(hinge[0]), float(hinge[1])), scene.base_pose(),
                           start.hand_position, start.hand_rotation)
    angle_address = scene.model.joint("hinge").qposadr[0]
    base = BaseDrive(scene, speed=0.4, turn=0.8, acceleration=0.8)
    opened, lost, worst, bumped = 0.0, False, 0.0, 0
    model = scene.model
    hand_bodies = {model.body(n).id for n in ("gripper", "left_finger", "right_finger")}
    door_body = model.body("door").id
    body_geoms = {g for g in range(model.ngeom) if model.geom_contype[g] == 2 and
                  int(model.geom_bodyid[g]) not in hand_bodies}
    door_geoms = {g for g in range(model.ngeom) if int(model.geom_bodyid[g]) == door_body} | {
        model.geom("jamb_left").id, model.geom("jamb_right").id}
    began = scene.time
    open_s: float | None = None
    close_s: float | None = None
    held_open = 0.0
    while scene.time - began < time_limit:
        command = behaviour.update(scene.control_period, scene.base_pose(),
                                   reading(scene).hand_position)
        apply(scene, controller, command)
        scene.step()
        base.drive(command.base, scene.control_period)
        angle = abs(float(scene.data.qpos[angle_address]))
        opened = max(opened, angle)
        bumped += _bumped(scene, body_geoms, door_geoms)
        worst = max(worst, float(np.linalg.norm(controller.wrench[:2])))
        bar = np.asarray(scene.data.site("handle_centre").xpos)
        if float(np.linalg.norm(bar - scene.hand_world())) > 0.05:
            lost = True
        if behaviour.phase is DoorPhase.OPEN:
            if open_s is None:
                open_s = scene.time - began
            held_open += scene.control_period
            if held_open >= 0.5:
                behaviour.close()
        if behaviour.phase is DoorPhase.CLOSED:
            close_s = scene.time - began - (open_s or 0.0)
            break
    scene.grip(False)
    for _ in range(30):  # let go
        apply(scene, controller, Command(controller.target_position,
                                         controller.target_rotation, Compliance(),
                                         gripper_closed=False))
        scene.step()
    closed = math.degrees(abs(float(scene.data.qpos[angle_address])))
    return DoorResult(door, round(math.degrees(opened), 2), round(closed, 2), lost,
                      None if open_s is None else round(open_s, 2),
                      None if close_s is None else round(close_s, 2), round(worst, 1), bumped,
                      scene.time, round(hinge_error, 3), round(handle_error, 3))


def _close_fingers(scene: InteractionScene, rest: np.ndarray,
                   steps: int) -> tuple[ComplianceController, ArmReading]:
    """Close the gripper where the hand is, holding it there compliantly for ``steps``
    control periods; the controller and the reading once the fingers are closed."""
    scene.grip(True)
    start = reading(scene)
    controller = ComplianceController(Compliance(), start.hand_position, start.hand_rotation,
                                      rest=rest)
    for _ in range(steps):
        apply(scene, controller, Command(start.hand_position, start.hand_rotation,
                                         Compliance(), gripper_closed=True))
        scene.step()
    return controller, reading(scene)
