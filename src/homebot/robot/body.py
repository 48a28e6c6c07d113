"""The ``Body`` port: what a robot's drivers offer, below the ``Robot`` port.

A body takes base velocity commands, reports odometry and laser scans, points
its head, and (as later parts are fitted) gives camera images, arm, gripper,
wrist force-torque, microphone and speaker. Time advances in ticks: a command
holds until it is replaced, and each ``tick`` moves the body and refreshes its
sensors. Everything here is what the drivers measure, never ground truth.

``SimBody`` (homebot.sim) implements it over the simulated home; ``RosBody``
(homebot.transport) over a robot's ROS 2 drivers. The action/perception layer
(localisation, navigation, perception, manipulation) sees the world only
through this port.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path

import numpy as np

from homebot.errors import BodyError, PartMissing
from homebot.geometry import Pose
from homebot.robot.camera import RgbdFrame

__all__ = [
    "Arm",
    "ArmState",
    "Body",
    "DriveKind",
    "Gripper",
    "GripperState",
    "HeadState",
    "JointTarget",
    "LaserScan",
    "Microphone",
    "Odometry",
    "Speaker",
    "Twist",
    "VelocityLimits",
    "Wrench",
]


class DriveKind(StrEnum):
    """How the base moves."""

    OMNIDIRECTIONAL = "omnidirectional"  #: any planar velocity (Cosero's base)
    DIFFERENTIAL = "differential"  #: forward speed and turn rate only; vy is ignored


@dataclass(frozen=True, slots=True)
class Twist:
    """A base velocity in the robot's frame: vx forward, vy left (m/s), wz turn (rad/s)."""

    vx: float = 0.0
    vy: float = 0.0
    wz: float = 0.0

    def is_zero(self) -> bool:
        return self.vx == 0.0 and self.vy == 0.0 and self.wz == 0.0


def _positive(value: float, what: str) -> float:
    if not (math.isfinite(value) and value > 0):
        raise BodyError(f"{what} must be a positive number, not {value!r}; "
                        "a robot with a limit of 0 cannot move")
    return value


@dataclass(frozen=True, slots=True)
class VelocityLimits:
    """The base's limits; every command is clipped to them."""

    linear: float = 0.5  #: m/s
    angular: float = 1.2  #: rad/s
    linear_acceleration: float = 1.0  #: m/s²
    angular_acceleration: float = 2.5  #: rad/s²

    def __post_init__(self) -> None:
        _positive(self.linear, "the linear velocity limit")
        _positive(self.angular, "the angular velocity limit")
        _positive(self.linear_acceleration, "the linear acceleration limit")
        _positive(self.angular_acceleration, "the angular acceleration limit")

    def clip(self, twist: Twist, drive: DriveKind) -> Twist:
        """The command as the base will take it: within limits, no sideways on a differential."""
        vy = twist.vy if drive is DriveKind.OMNIDIRECTIONAL else 0.0
        speed = math.hypot(twist.vx, vy)
        scale = self.linear / speed if speed > self.linear else 1.0
        wz = max(-self.angular, min(self.angular, twist.wz))
        return Twist(twist.vx * scale, vy * scale, wz)


@dataclass(frozen=True, slots=True)
class Odometry:
    """Where the wheels say the robot is, in the odometry frame (it drifts), and how fast."""

    stamp: float
    pose: Pose
    twist: Twist


@dataclass(frozen=True)
class LaserScan:
    """One sweep of the 2-D laser, as ``sensor_msgs/LaserScan`` has it.

    ``ranges[i]`` is the distance measured along ``angle_min + i * angle_increment``
    in the sensor's frame; ``inf`` means no return within ``range_max``. ``mount``
    is the sensor's pose in the robot's frame.
    """

    stamp: float
    angle_min: float
    angle_increment: float
    range_min: float
    range_max: float
    ranges: np.ndarray
    mount: Pose = field(default_factory=lambda: Pose(0.0, 0.0, 0.0))

    def angles(self) -> np.ndarray:
        """The beam angles in the sensor's frame."""
        return self.angle_min + self.angle_increment * np.arange(len(self.ranges))

    def valid(self) -> np.ndarray:
        """Which beams have a return within the sensor's range."""
        valid: np.ndarray = np.isfinite(self.ranges) & (self.ranges >= self.range_min) & \
            (self.ranges <= self.range_max)
        return valid

    def points(self) -> np.ndarray:
        """The returns as (n, 2) points in the robot's frame (beams with no return dropped)."""
        keep = self.valid()
        angles = self.angles()[keep] + self.mount.theta
        ranges = self.ranges[keep]
        return np.column_stack((self.mount.x + ranges * np.cos(angles),
                                self.mount.y + ranges * np.sin(angles)))


@dataclass(frozen=True, slots=True)
class HeadState:
    """The pan-tilt head: pan left positive, tilt down positive (radians)."""

    pan: float = 0.0
    tilt: float = 0.0


@dataclass(frozen=True)
class ArmState:
    """The arm's joints as ``sensor_msgs/JointState`` has them, and the torso lift's height."""

    stamp: float
    names: tuple[str, ...]
    positions: np.ndarray  #: radians
    velocities: np.ndarray  #: rad/s
    efforts: np.ndarray  #: N·m
    torso: float  #: metres the torso is lifted


@dataclass(frozen=True)
class JointTarget:
    """Where the arm's joints should go (radians, in ``Arm.joint_names`` order), the torso's
    height (None: stay) and extra joint torques for compliance (None: none)."""

    positions: tuple[float, ...]
    torso: float | None = None
    torques: tuple[float, ...] | None = None


@dataclass(frozen=True, slots=True)
class GripperState:
    """The parallel gripper: metres between the fingers and the force they squeeze with."""

    stamp: float
    width: float
    effort: float  #: newtons, positive when squeezing
    max_width: float


@dataclass(frozen=True)
class Wrench:
    """The wrist's force-torque reading, in the sensor's frame (``geometry_msgs/Wrench``)."""

    stamp: float
    force: np.ndarray  #: newtons (x, y, z)
    torque: np.ndarray  #: N·m


class Arm(ABC):
    """The arm's joint interface: state, position targets that hold until replaced, and
    the robot description (an MJCF file, as ROS's ``robot_description`` names the URDF)."""

    joint_names: tuple[str, ...]
    limits: tuple[tuple[float, float], ...]  #: per joint, radians
    torso_limits: tuple[float, float]
    payload: float  #: kilograms the arm is rated to lift

    @abstractmethod
    def state(self) -> ArmState:
        """The joints after the last tick."""

    @abstractmethod
    def command(self, target: JointTarget) -> None:
        """Drive the joints to ``target`` (taking effect at the next tick)."""

    @abstractmethod
    def description(self) -> Path:
        """The arm's MJCF model, for planning."""


class Gripper(ABC):
    """A parallel gripper."""

    @abstractmethod
    def state(self) -> GripperState:
        """The fingers after the last tick."""

    @abstractmethod
    def command(self, width: float, force: float | None = None) -> None:
        """Move the fingers to ``width`` apart, squeezing with at most ``force`` newtons."""


class Speaker(ABC):
    """The loudspeaker: plays 16-bit mono samples at ``rate`` (as audio_common's
    ``AudioData``). Playing takes the sound's duration on the body's clock."""

    rate: int  #: samples per second

    @abstractmethod
    def play(self, samples: np.ndarray, *, text: str | None = None) -> float:
        """Play ``samples`` (int16 at ``rate``) to the end; ``text`` is what they say, for
        the log. Returns the seconds it took."""


class Microphone(ABC):
    """The microphone: 16-bit mono samples at ``rate``."""

    rate: int  #: samples per second

    @abstractmethod
    def read(self) -> np.ndarray:
        """The sound since the previous ``read`` (int16 at ``rate``; at most the last
        30 seconds)."""


class Body(ABC):
    """The port between the action/perception layer and a robot's drivers.

    Commands take effect at the next ``tick``; sensors show the state after the
    last tick. An engaged emergency stop brings the base to rest within one tick
    and ignores velocity commands until released.
    """

    drive: DriveKind
    limits: VelocityLimits
    radius: float  #: the base's footprint radius, metres
    tick_period: float  #: simulated (or real) seconds per tick

    @abstractmethod
    def now(self) -> float:
        """Seconds on the body's clock."""

    @abstractmethod
    def tick(self, ticks: int = 1) -> None:
        """Let ``ticks`` control periods pass: move, then sense."""

    @abstractmethod
    def command_velocity(self, twist: Twist) -> None:
        """Drive with ``twist`` (clipped to the limits) until the next command."""

    @abstractmethod
    def odometry(self) -> Odometry:
        """The wheels' latest estimate."""

    @abstractmethod
    def scan(self) -> LaserScan:
        """The laser's latest sweep."""

    @abstractmethod
    def head(self) -> HeadState:
        """Where the head points."""

    @abstractmethod
    def point_head(self, pan: float, tilt: float) -> None:
        """Turn the head (clipped to its joint limits)."""

    @abstractmethod
    def emergency_stop(self, engaged: bool = True) -> None:
        """Engage (or release) the emergency stop."""

    @property
    @abstractmethod
    def stopped(self) -> bool:
        """Whether the emergency stop is engaged."""

    # Parts that later modules fit. A body without them says so.

    def camera(self) -> RgbdFrame:
        """The head's RGB-D camera image, taken now with the head where it points."""
        raise PartMissing("RGB-D camera")

    def last_camera(self) -> RgbdFrame | None:
        """The latest image ``camera`` took (None: none yet): reading it takes no new
        image."""
        return None

    def view(self) -> RgbdFrame | None:
        """What the head camera sees now, for a watcher (the console's page), not for the
        robot: watching changes nothing the robot senses or does. A simulated body draws
        it apart from the robot's own images; a body that cannot gives the latest image
        ``camera`` took (None: none yet)."""
        return self.last_camera()

    def face_crops(self, views: int) -> list[np.ndarray]:
        """The head camera's close-ups of the face of the person in front (grey images), so
        many ``views`` as a face tracker crops over a second or two; none when nobody
        stands in front of the head."""
        raise PartMissing("face tracker")

    def arm(self) -> Arm:
        """The arm's joint interface."""
        raise PartMissing("arm")

    def gripper(self) -> Gripper:
        """The gripper."""
        raise PartMissing("gripper")

    def wrist_wrench(self) -> Wrench:
        """The wrist's force-torque reading."""
        raise PartMissing("wrist force-torque sensor")

    def microphone(self) -> Microphone:
        """The microphone: the sound that reached the robot."""
        raise PartMissing("microphone")

    def speaker(self) -> Speaker:
        """The loudspeaker the robot speaks through."""
        raise PartMissing("speaker")
