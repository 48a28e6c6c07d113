"""``SimBody``: the Body port over the simulated home.

A kinematic base (omnidirectional or differential, as the world file says)
moves under velocity commands within its limits; a bumper stops it on
contact, and every contact is a collision in the simulation's truth. Odometry
integrates the motion with a systematic and a random error, so it drifts. The
laser is cast against the true geometry and the legs of people, some of whom
walk about on their own. Time passes only in ticks of simulated time.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
from shapely.geometry import Point as ShapelyPoint

from homebot.errors import BodyError, PartMissing
from homebot.geometry import Pose, wrap_angle
from homebot.robot import (
    Arm,
    Body,
    DriveKind,
    Gripper,
    HeadState,
    LaserScan,
    Microphone,
    Odometry,
    RgbdFrame,
    Speaker,
    Twist,
    VelocityLimits,
    Wrench,
)
from homebot.sim.audio import AudioScene, SimMicrophone, SimSpeaker
from homebot.sim.body_tracker import PeopleArms, person_solids
from homebot.sim.camera import (
    CameraSimulator,
    Limb,
    SceneGeometry,
    Solid,
    door_solids,
    object_yaw,
)
from homebot.sim.components import ComponentSimulation
from homebot.sim.faces import FaceCamera
from homebot.sim.geometry import TrueGeometry
from homebot.sim.hands import ArmDriver, SimHands
from homebot.sim.hearing import PeopleHearing, PersonVoice
from homebot.sim.laser import LaserSimulator
from homebot.sim.simulation import Simulation
from homebot.sim.walkers import PeopleWalking
from homebot.world import DoorState, LaserModel, object_catalogue, surface_height

__all__ = ["FOOT_RADIUS", "OdometryNoise", "SimBody"]

#: The base touches people at their legs and feet: this far round each leg's centre (the
#: laser, higher up, sees the legs themselves, ``LEG_RADIUS``).
FOOT_RADIUS = 0.1
#: Walkers do not step closer to the robot's centre than its radius and this much.
_PERSONAL_SPACE = 0.3
_LASER_MOUNT = Pose(0.15, 0.0, 0.0)
_PAN_LIMIT = 2.6
_TILT_LIMITS = (-0.4, 0.9)
_CONTACT_HYSTERESIS = 0.03  #: metres clear of an obstacle before a new touch counts again
_TRAJECTORY_STEP = 0.1  #: metres between recorded trajectory points
_LOOKING_REACH = 1.0  #: metres from a placement within which the robot looks at it
_CATCH_UP_STEP = 0.5  #: seconds per walking step when time passed outside the ticks
# Seeds of the body's own random streams, apart from the simulation's disturbances.
# A watcher's view has a stream of its own: drawing it takes nothing from the robot's.
_SENSOR_STREAM, _WALKER_STREAM, _CAMERA_STREAM, _VIEW_STREAM = 101, 202, 404, 505


class OdometryNoise:
    """How wheel odometry errs: a per-run scale error and per-tick noise, each per metre/radian."""

    def __init__(self, scale: float = 0.01, translation: float = 0.02,
                 rotation: float = 0.02) -> None:
        self.scale, self.translation, self.rotation = scale, translation, rotation


class SimBody(Body):
    """A robot body in a ``Simulation``.

    Args:
        simulation: the ground truth; the body moves ``simulation.robot_pose``.
        walkers: how many people walk about (chosen in name order, the operator last),
            or their names.
        tick_rate: control ticks per simulated second (≥ 20).
        laser: the laser (default: the world's).
        odometry_noise: how the wheels err.
        components: the robot's own components (``homebot.sim.components``), if modelled:
            they crash on the body's clock, and no laser beam returns unless the
            component ``laser`` is running.
        face_half_angle: radians off the head's axis within which a face is the one the
            face tracker crops (``face_crops``).
        voice: how people sound when they answer the robot aloud (``homebot.sim.hearing``;
            None: they hear it and act, but say nothing).
    """

    def __init__(self, simulation: Simulation, *, walkers: int | Sequence[str] = 0,
                 tick_rate: float = 20.0, laser: LaserModel | None = None,
                 odometry_noise: OdometryNoise | None = None,
                 components: ComponentSimulation | None = None,
                 face_half_angle: float = 0.25, voice: PersonVoice | None = None) -> None:
        if not (math.isfinite(tick_rate) and tick_rate >= 20.0):
            raise BodyError(f"tick_rate must be at least 20 Hz, not {tick_rate!r}")
        self.sim = simulation
        world = simulation.world
        robot = world.robot
        self.drive = DriveKind(robot.drive)
        self.limits = VelocityLimits(robot.speed, robot.angular_speed)
        self.radius = robot.radius
        self.tick_period = 1.0 / tick_rate
        self.geometry = TrueGeometry.of(world)
        sensor_rng = np.random.default_rng([simulation.seed, _SENSOR_STREAM])
        self._rng = sensor_rng
        self.laser = LaserSimulator(self.geometry, laser or robot.laser, _LASER_MOUNT, sensor_rng)
        noise = odometry_noise or OdometryNoise()
        self._noise = noise
        self._scale_error = (1.0 + sensor_rng.normal(0.0, noise.scale),
                             1.0 + sensor_rng.normal(0.0, noise.scale))
        self.people = PeopleWalking(simulation, self._walker_names(walkers),
                                    random.Random(f"{simulation.seed}:{_WALKER_STREAM}"))
        self._command = Twist()
        self._velocity = Twist()
        self._stopped = False
        self._odometry = (0.0, 0.0, 0.0)
        self._head = HeadState()
        self._last_camera: RgbdFrame | None = None
        self._in_contact = False
        self._last_tick_end = simulation.clock.now()
        self._scan: LaserScan | None = None
        self.components = components
        self._catalogue = object_catalogue(world)
        scene = SceneGeometry.of(world)
        self.camera_simulator = CameraSimulator(
            scene, np.random.default_rng([simulation.seed, _CAMERA_STREAM]))
        #: the same camera drawn for watchers (``view``), with its own noise
        self._viewer = CameraSimulator(
            scene, np.random.default_rng([simulation.seed, _VIEW_STREAM]))
        #: how people move their arms, as the head camera sees them
        self.arms = PeopleArms(simulation.seed)
        self._face_camera = FaceCamera(self, half_angle=face_half_angle)
        #: called after every tick: referees watching the truth as it unfolds (never the robot)
        self.referees: list[Callable[[], None]] = []
        self._travelled_since_point = 0.0
        self._trajectory: list[tuple[float, float]] = [self._rounded_position()]
        #: the simulation's sounds: what the speaker plays and the microphone hears
        self.audio = AudioScene(simulation.clock.now, simulation.seed)
        #: the people hearing the robot, answering aloud and doing what it asks
        self.hearing = PeopleHearing(simulation, self.audio, voice, self.people.walk_route)
        self._speaker = SimSpeaker(self.audio, simulation.events, self.tick, self.tick_period,
                                   self.hearing.robot_said)
        self._microphone = SimMicrophone(self.audio, simulation.clock.now)
        #: the arm, gripper and wrist sensor in MuJoCo where the robot stands
        arm_model = world.arm_model_path()
        self.hands = SimHands(simulation, self.tick_period, arm_model, self.hearing)
        if arm_model is not None and _has_mujoco():
            from homebot.sim.arm import load_arm_spec

            load_arm_spec(arm_model)  # a broken model is an error at the start, not mid-task

    def _walker_names(self, walkers: int | Sequence[str]) -> list[str]:
        people = self.sim.people
        if isinstance(walkers, int):
            if walkers < 0:
                raise BodyError(f"walkers must be 0 or more, not {walkers}")
            operator = self.sim.world.model.operator
            order = sorted(people, key=lambda name: (name == operator, name))
            return order[:walkers]
        unknown = [name for name in walkers if name not in people]
        if unknown:
            raise BodyError(f"unknown walker(s) {', '.join(unknown)}; "
                            f"people: {', '.join(sorted(people))}")
        return list(walkers)

    # ------------------------------------------------------------ the port

    def now(self) -> float:
        return self.sim.clock.now()

    def command_velocity(self, twist: Twist) -> None:
        self._command = self.limits.clip(twist, self.drive)

    def emergency_stop(self, engaged: bool = True) -> None:
        self._stopped = engaged
        if engaged:
            self._command = Twist()

    @property
    def stopped(self) -> bool:
        return self._stopped

    def odometry(self) -> Odometry:
        return Odometry(self.now(), Pose(*self._odometry), self._velocity)

    def scan(self) -> LaserScan:
        # One scan per tick; time that passed outside the ticks (a door opened, people
        # walked on while the robot talked) gives a new one.
        if self._scan is None or self._scan.stamp != self.now():
            self._scan = self.laser.scan(self.now(), self.sim.robot_pose,
                                         self.sim.closed_doors(), self.people.legs(),
                                         self.sim.leaves_swung_back)
            components = self.components
            if components is not None and components.state.get("laser", "running") != "running":
                # a laser that is off or crashed sees nothing: no beam returns
                self._scan = replace(self._scan, ranges=np.full_like(self._scan.ranges, np.inf))
        return self._scan

    def head(self) -> HeadState:
        return self._head

    def point_head(self, pan: float, tilt: float) -> None:
        self._head = HeadState(max(-_PAN_LIMIT, min(_PAN_LIMIT, pan)),
                               max(_TILT_LIMITS[0], min(_TILT_LIMITS[1], tilt)))

    def camera(self) -> RgbdFrame:
        """The head camera's frame of the true home: furniture, walls, shut doors' leaves
        and handles, the objects on their surfaces and the people, their arms as they move
        them at this moment (``homebot.sim.camera``, ``sim.body_tracker``)."""
        self._first_looks()
        self._last_camera = self.camera_simulator.render(self.now(), self.sim.robot_pose,
                                                         self._head, self._solids())
        return self._last_camera

    def last_camera(self) -> RgbdFrame | None:
        return self._last_camera

    def view(self) -> RgbdFrame:
        """What the head camera sees now, drawn for a watcher: the scene ``camera`` draws,
        with the viewer's own noise; no first looks (nobody moves an object because a page
        watches), and the robot's latest image stays its own."""
        return self._viewer.render(self.now(), self.sim.robot_pose, self._head, self._solids())

    def _first_looks(self) -> None:
        """The first time the camera sees a placement the robot stands at, someone may
        just have moved an object from it (``Simulation.maybe_move_during_task``)."""
        here = ShapelyPoint(self.sim.robot_pose[:2])
        for name, placement in sorted(self.sim.world.placements.items()):
            if placement.footprint.distance(here) <= _LOOKING_REACH:
                self.sim.maybe_move_during_task(name)

    def face_crops(self, views: int) -> list[np.ndarray]:
        """Rendered views of the face of the person in front (``homebot.sim.faces``)."""
        return self._face_camera(views)

    def arm(self) -> Arm:
        """The arm (MuJoCo physics where the robot stands)."""
        return self._arm_driver().arm()

    def gripper(self) -> Gripper:
        return self._arm_driver().gripper()

    def wrist_wrench(self) -> Wrench:
        return self._arm_driver().wrist_wrench()

    def _arm_driver(self) -> ArmDriver:
        if not _has_mujoco():
            raise PartMissing("arm in physics (MuJoCo): pip install 'homebot[embodied]'")
        return self.hands.driver()

    def _solids(self) -> list[Solid | Limb]:
        sim = self.sim
        solids: list[Solid | Limb] = []
        for name, where in sorted(sim.object_location.items()):
            placement = sim.world.placements.get(where or "")
            if placement is None:
                continue  # in a hand, given away, on the floor or gone
            entry = self._catalogue[name]
            x, y = sim.position_on(name, placement.name)
            solids.append(Solid(entry.shape, entry.extent, entry.rgb, x, y,
                                surface_height(placement.model), object_yaw(name, sim.seed)))
        for name, state in sorted(sim.people.items()):
            solids.extend(person_solids(sim.world, name, state.model, state.posture,
                                        state.position, self.people.facing(name)))
            solids.extend(self.arms.solids(name, state.model, state.posture, state.position,
                                           sim.robot_pose[:2], self.now()))
        for door, door_state in sorted(sim.door_state.items()):
            if door_state is not DoorState.OPEN:
                solids.extend(door_solids(sim.world, door))
        return solids

    def speaker(self) -> Speaker:
        """The loudspeaker: its sound goes into ``audio`` and the body ticks while it
        plays (``homebot.sim.audio``)."""
        return self._speaker

    def microphone(self) -> Microphone:
        """The microphone: ``audio`` since the previous read."""
        return self._microphone

    def tick(self, ticks: int = 1) -> None:
        for _ in range(ticks):
            self._tick_once()
        self._scan = None

    # ------------------------------------------------------------ ground truth (not the port)

    def teleport(self, pose: Pose) -> None:
        """Carry the robot elsewhere without its wheels knowing (kidnapping)."""
        self.sim.robot_pose = (pose.x, pose.y, pose.theta)
        self._scan = None
        self.sim.events.record("sim.disturbance", what="kidnapped", to=[pose.x, pose.y])

    def true_pose(self) -> Pose:
        return Pose(*self.sim.robot_pose)

    def _flush_trajectory(self) -> None:
        """Once the base comes to rest: the path driven since, as a ``robot.trajectory`` event."""
        points, here = self._trajectory, self._rounded_position()
        if points[-1] != here:
            points.append(here)
        if len(points) > 1:
            self.sim.events.record("robot.trajectory", world=self.sim.world.name,
                                   points=[list(p) for p in points])
            self.sim.trail.extend(points[1:])
        self._trajectory = [here]

    # ------------------------------------------------------------ one tick

    def _catch_up_people(self) -> None:
        """Time that passed outside the ticks (the robot grasping, talking) passes for walkers."""
        gap = self.sim.clock.now() - self._last_tick_end
        robot = self.sim.robot_pose[:2]
        while gap > 1e-9:
            step = min(gap, _CATCH_UP_STEP)
            self.people.advance(step, robot, self.radius + _PERSONAL_SPACE)
            gap -= step

    def _tick_once(self) -> None:
        self._catch_up_people()
        dt = self.tick_period
        was_moving = not self._velocity.is_zero()
        target = Twist() if self._stopped else self._command
        self._velocity = Twist() if self._stopped else self._accelerate(target, dt)
        moved = self._move(dt)
        if was_moving and self._velocity.is_zero():
            self._flush_trajectory()
        self._odometry_step(*moved)
        self.people.advance(dt, self.sim.robot_pose[:2], self.radius + _PERSONAL_SPACE)
        self._last_tick_end = self.sim.clock.advance(dt)
        self.hands.advance(dt)
        for watch in self.referees:
            watch()
        if self.components is not None:  # the components live on the body's clock
            self.components.advance(max(0.0, self._last_tick_end - self.components.now))

    def _accelerate(self, target: Twist, dt: float) -> Twist:
        linear = self.limits.linear_acceleration * dt
        angular = self.limits.angular_acceleration * dt
        now = self._velocity
        return Twist(now.vx + max(-linear, min(linear, target.vx - now.vx)),
                     now.vy + max(-linear, min(linear, target.vy - now.vy)),
                     now.wz + max(-angular, min(angular, target.wz - now.wz)))

    def _move(self, dt: float) -> tuple[float, float, float]:
        """Move by the current velocity unless the bumper meets something; the motion in the
        robot's frame (forward, left, turn)."""
        velocity = self._velocity
        if velocity.is_zero():
            return (0.0, 0.0, 0.0)
        x, y, theta = self.sim.robot_pose
        middle = theta + velocity.wz * dt / 2
        forward, left = velocity.vx * dt, velocity.vy * dt
        new_x = x + forward * math.cos(middle) - left * math.sin(middle)
        new_y = y + forward * math.sin(middle) + left * math.cos(middle)
        new_theta = wrap_angle(theta + velocity.wz * dt)
        obstacle = self._obstacle_at(new_x, new_y) if (forward or left) else None
        if obstacle is not None:
            if not self._in_contact:
                self.sim.collisions.append({"time": round(self.now(), 3), "with": obstacle,
                                            "at": [round(new_x, 3), round(new_y, 3)]})
                self.sim.events.record("sim.collision", what=obstacle,
                                       at=[round(new_x, 3), round(new_y, 3)])
            self._in_contact = True
            self._velocity = Twist()
            return (0.0, 0.0, 0.0)
        # One touch is one collision: contact ends only once the robot is clear again.
        if self._in_contact:
            self._in_contact = self._obstacle_at(new_x, new_y, _CONTACT_HYSTERESIS) is not None
        self.sim.robot_pose = (new_x, new_y, new_theta)
        self._note_trajectory(math.hypot(forward, left))
        return (forward, left, velocity.wz * dt)

    def _obstacle_at(self, x: float, y: float, margin: float = 0.0) -> str | None:
        """What the robot's footprint at (x, y), grown by ``margin``, would touch, or None."""
        radius = self.radius + margin
        if self.geometry.clearance(x, y, self.sim.closed_doors(),
                                   self.sim.leaves_swung_back) < radius:
            return "wall or furniture"
        for name, leg in self.people.named_legs():
            if math.dist((x, y), leg) < radius + FOOT_RADIUS:
                return f"person {name}"
        return None

    def _odometry_step(self, forward: float, left: float, turn: float) -> None:
        if forward == 0.0 and left == 0.0 and turn == 0.0:
            return
        noise = self._noise
        rng = self._rng
        distance = math.hypot(forward, left)
        forward = forward * self._scale_error[0] + rng.normal(0.0, noise.translation * distance)
        left = left * self._scale_error[0] + rng.normal(0.0, noise.translation * distance)
        turn = turn * self._scale_error[1] + rng.normal(
            0.0, noise.rotation * abs(turn) + 0.1 * noise.rotation * distance)
        x, y, theta = self._odometry
        middle = theta + turn / 2
        self._odometry = (x + forward * math.cos(middle) - left * math.sin(middle),
                          y + forward * math.sin(middle) + left * math.cos(middle),
                          wrap_angle(theta + turn))

    def _note_trajectory(self, distance: float) -> None:
        self._travelled_since_point += distance
        if self._travelled_since_point >= _TRAJECTORY_STEP:
            self._travelled_since_point = 0.0
            self._trajectory.append(self._rounded_position())

    def _rounded_position(self) -> tuple[float, float]:
        x, y, _ = self.sim.robot_pose
        return (round(x, 3), round(y, 3))


def _has_mujoco() -> bool:
    import importlib.util

    return importlib.util.find_spec("mujoco") is not None


