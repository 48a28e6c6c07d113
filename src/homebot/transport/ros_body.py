"""``RosBody``: the Body port over a robot's ROS 2 drivers, and ``BodyServer``, a body serving them.

``RosBody`` sends ``geometry_msgs/Twist`` on ``/cmd_vel`` once per tick and takes the
tick as done when the drivers' next ``nav_msgs/Odometry`` (``/odom``) and
``sensor_msgs/LaserScan`` (``/scan``) have come; the laser's mount is read from the scan's
frame via the static transform ``base_link -> laser`` on ``/tf_static``. A real robot's
drivers publish at their own rate, so a tick is one odometry period; ``BodyServer``
(``homebot sim serve --body``) ticks its ``Body`` once per ``/cmd_vel`` it receives, so
the two run in lockstep and a seeded run is the same over ROS 2 as in one process. It
also publishes the simulator's true pose on ``/homebot/truth`` (for benchmarks only).

Both use the reliable default QoS for ``/cmd_vel``, ``/odom`` and ``/scan`` (a lockstep
cannot lose a tick); a robot whose laser driver offers best effort needs ``sensor_qos``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from homebot.geometry import Pose
from homebot.robot import Body, DriveKind, HeadState, LaserScan, Odometry, Twist, VelocityLimits
from homebot.transport.messages import orient, pose_of, seconds, stamp, yaw_of
from homebot.transport.naming import DEFAULT_QOS, MAP_QOS, SENSOR_QOS
from homebot.transport.node import Node, TransportError, log

__all__ = ["BodyServer", "RosBody"]

_TICK_TIMEOUT = 2.0  #: seconds (wall clock) a tick may take before the body counts as lost


class RosBody(Body):
    """A robot body reached over ROS 2 topics."""

    def __init__(self, node: Node, *, drive: DriveKind, limits: VelocityLimits, radius: float,
                 tick_period: float, sensor_qos: bool = False,
                 timeout: float = _TICK_TIMEOUT) -> None:
        self.node, self.drive, self.limits = node, drive, limits
        self.radius, self.tick_period, self.timeout = radius, tick_period, timeout
        qos = SENSOR_QOS if sensor_qos else DEFAULT_QOS
        self._cmd_vel = node.publisher("/cmd_vel", "geometry_msgs/msg/Twist")
        self._odom = node.subscription("/odom", "nav_msgs/msg/Odometry", qos)
        self._scan = node.subscription("/scan", "sensor_msgs/msg/LaserScan", qos)
        self._tf_static = node.subscription("/tf_static", "tf2_msgs/msg/TFMessage", MAP_QOS)
        self._head_command = node.publisher("/head/command", "sensor_msgs/msg/JointState")
        self._command = Twist()
        self._stopped = False
        self._head = HeadState()
        self._mount = Pose(0.0, 0.0, 0.0)
        self._last_odometry: Odometry | None = None
        self._last_scan: LaserScan | None = None

    def connect(self, timeout: float) -> None:
        """Wait for the drivers, then for the first odometry and scan."""
        if not (self._cmd_vel.wait_for_subscribers(1, timeout)
                and self._odom.wait_for_publishers(1, timeout)
                and self._scan.wait_for_publishers(1, timeout)):
            raise TransportError(f"no robot drivers on /cmd_vel, /odom and /scan within "
                                 f"{timeout:g} s (ROS 2 domain {self.node.settings.domain_id})")
        self._read_mount(timeout)
        self.tick(0)

    def _read_mount(self, timeout: float) -> None:
        for message in self._tf_static.wait(timeout):
            for transform in message.transforms:
                if transform.header.frame_id == "base_link":
                    moved = transform.transform
                    self._mount = Pose(moved.translation.x, moved.translation.y,
                                       yaw_of(moved.rotation))

    # ------------------------------------------------------------ the port

    def now(self) -> float:
        return self._last_odometry.stamp if self._last_odometry else 0.0

    def tick(self, ticks: int = 1) -> None:
        """Send the command ``ticks`` times, each time waiting for the next odometry and scan.

        ``tick(0)`` only waits for fresh sensors (when none came yet).
        """
        for _ in range(ticks):
            self._send(Twist() if self._stopped else self._command)
            self._await(self.now() + self.tick_period * 0.5)
        if ticks == 0 and self._last_odometry is None:
            self._await(-math.inf)

    def _send(self, twist: Twist) -> None:
        message = self.node.types.new("geometry_msgs/msg/Twist")
        message.linear.x, message.linear.y, message.angular.z = twist.vx, twist.vy, twist.wz
        self._cmd_vel.publish(message)

    def _await(self, after: float) -> None:
        """Wait until an odometry and a scan stamped after ``after`` (and alike) have come."""
        odometry, scan = self._last_odometry, self._last_scan
        arrived = self._odom.take()
        for _ in range(int(self.timeout / 0.05) + 1):
            for message in arrived:
                odometry = _odometry(message)
            for message in self._scan.take():
                scan = _scan(message, self._mount)
            if odometry is not None and scan is not None and odometry.stamp > after and \
                    abs(scan.stamp - odometry.stamp) < self.tick_period * 0.5:
                self._last_odometry, self._last_scan = odometry, scan
                return
            arrived = self._odom.wait(0.05)
        raise TransportError(f"the robot's drivers sent no odometry and scan for "
                             f"{self.timeout:g} s; the robot is lost")

    def command_velocity(self, twist: Twist) -> None:
        self._command = self.limits.clip(twist, self.drive)

    def odometry(self) -> Odometry:
        if self._last_odometry is None:
            raise TransportError("no odometry yet: connect() first")
        return self._last_odometry

    def scan(self) -> LaserScan:
        if self._last_scan is None:
            raise TransportError("no laser scan yet: connect() first")
        return self._last_scan

    def head(self) -> HeadState:
        return self._head

    def point_head(self, pan: float, tilt: float) -> None:
        self._head = HeadState(pan, tilt)
        self._head_command.publish(self.node.types.new(
            "sensor_msgs/msg/JointState", name=["head_pan_joint", "head_tilt_joint"],
            position=[pan, tilt]))

    def emergency_stop(self, engaged: bool = True) -> None:
        self._stopped = engaged
        if engaged:
            self._send(Twist())

    @property
    def stopped(self) -> bool:
        return self._stopped


def _odometry(message: Any) -> Odometry:
    twist = message.twist.twist
    return Odometry(seconds(message.header.stamp), pose_of(message.pose.pose),
                    Twist(twist.linear.x, twist.linear.y, twist.angular.z))


def _scan(message: Any, mount: Pose) -> LaserScan:
    ranges = np.asarray(message.ranges, dtype=float)
    ranges[~np.isfinite(ranges) | (ranges > message.range_max)] = np.inf
    return LaserScan(seconds(message.header.stamp), float(message.angle_min),
                     float(message.angle_increment), float(message.range_min),
                     float(message.range_max), ranges, mount)


class BodyServer:
    """Serves a ``Body`` on ROS 2 topics, one tick per ``/cmd_vel`` (lockstep)."""

    def __init__(self, node: Node, body: Body, truth: Callable[[], Pose] | None = None) -> None:
        self.node, self.body, self.truth = node, body, truth
        self._cmd_vel = node.subscription("/cmd_vel", "geometry_msgs/msg/Twist")
        self._odom = node.publisher("/odom", "nav_msgs/msg/Odometry")
        self._scan = node.publisher("/scan", "sensor_msgs/msg/LaserScan")
        self._tf = node.publisher("/tf", "tf2_msgs/msg/TFMessage")
        self._tf_static = node.publisher("/tf_static", "tf2_msgs/msg/TFMessage", MAP_QOS)
        self._truth = node.publisher("/homebot/truth", "geometry_msgs/msg/PoseStamped")
        mount = body.scan().mount
        self._tf_static.publish(self._transforms([("base_link", "laser", mount)]))
        self.publish()

    def spin_once(self, timeout: float = 0.1) -> int:
        """Tick once per velocity command that came (waiting up to ``timeout`` s)."""
        commands = self._cmd_vel.wait(timeout)
        for command in commands:
            twist = Twist(command.linear.x, command.linear.y, command.angular.z)
            if not all(math.isfinite(value) for value in (twist.vx, twist.vy, twist.wz)):
                log.warning("/cmd_vel: a velocity that is not finite (%s); the body stops",
                            twist)
                twist = Twist(0.0, 0.0, 0.0)
            self.body.command_velocity(twist)
            self.body.tick()
            self.publish()
        return len(commands)

    def publish(self) -> None:
        """The body's sensors after its last tick: scan, odometry, odom -> base_link, truth."""
        types, body = self.node.types, self.body
        now = body.now()
        scan = body.scan()
        header = types.new("std_msgs/msg/Header", stamp=stamp(types, now), frame_id="laser")
        count = len(scan.ranges)
        self._scan.publish(types.new(
            "sensor_msgs/msg/LaserScan", header=header, angle_min=scan.angle_min,
            angle_max=scan.angle_min + scan.angle_increment * (count - 1),
            angle_increment=scan.angle_increment, scan_time=body.tick_period,
            range_min=scan.range_min, range_max=scan.range_max,
            ranges=[float(value) for value in scan.ranges]))
        odometry = body.odometry()
        message = types.new("nav_msgs/msg/Odometry", header=types.new(
            "std_msgs/msg/Header", stamp=stamp(types, now), frame_id="odom"),
            child_frame_id="base_link")
        _set_pose(message.pose.pose, odometry.pose)
        message.twist.twist.linear.x = odometry.twist.vx
        message.twist.twist.linear.y = odometry.twist.vy
        message.twist.twist.angular.z = odometry.twist.wz
        self._tf.publish(self._transforms([("odom", "base_link", odometry.pose)], now))
        if self.truth is not None:
            truth = types.new("geometry_msgs/msg/PoseStamped", header=types.new(
                "std_msgs/msg/Header", stamp=stamp(types, now), frame_id="map"))
            _set_pose(truth.pose, self.truth())
            self._truth.publish(truth)
        self._odom.publish(message)  # last: a tick is done when its odometry has come

    def _transforms(self, frames: list[tuple[str, str, Pose]], now: float = 0.0) -> Any:
        types = self.node.types
        transforms = []
        for parent, child, pose in frames:
            transform = types.new("geometry_msgs/msg/TransformStamped", header=types.new(
                "std_msgs/msg/Header", stamp=stamp(types, now), frame_id=parent),
                child_frame_id=child)
            transform.transform.translation.x = pose.x
            transform.transform.translation.y = pose.y
            orient(transform.transform.rotation, pose.theta)
            transforms.append(transform)
        return types.new("tf2_msgs/msg/TFMessage", transforms=transforms)


def _set_pose(message: Any, pose: Pose) -> None:
    message.position.x, message.position.y = pose.x, pose.y
    orient(message.orientation, pose.theta)
