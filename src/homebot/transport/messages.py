"""Small conversions between homebot's port types and ROS 2 messages (REP 103 units)."""

from __future__ import annotations

import math
from typing import Any

from homebot.geometry import Pose
from homebot.transport.types import MessageTypes

__all__ = ["pose_of", "pose_stamped", "seconds", "stamp", "yaw_of"]


def stamp(types: MessageTypes, time: float) -> Any:
    """A ``builtin_interfaces/msg/Time`` of ``time`` seconds."""
    sec = math.floor(time)
    return types.new("builtin_interfaces/msg/Time", sec=int(sec),
                     nanosec=min(999_999_999, round((time - sec) * 1e9)))


def seconds(time: Any) -> float:
    """Seconds of a ``builtin_interfaces/msg/Time``."""
    return float(time.sec) + float(time.nanosec) * 1e-9


def yaw_of(quaternion: Any) -> float:
    """The heading of a planar orientation quaternion."""
    return math.atan2(2.0 * (quaternion.w * quaternion.z + quaternion.x * quaternion.y),
                      1.0 - 2.0 * (quaternion.y ** 2 + quaternion.z ** 2))


def pose_stamped(types: MessageTypes, pose: Pose, time: float, frame: str = "map") -> Any:
    """A ``geometry_msgs/msg/PoseStamped`` of a planar pose."""
    message = types.new("geometry_msgs/msg/PoseStamped",
                        header=types.new("std_msgs/msg/Header", stamp=stamp(types, time),
                                         frame_id=frame))
    message.pose.position.x, message.pose.position.y = pose.x, pose.y
    message.pose.orientation.z = math.sin(pose.theta / 2.0)
    message.pose.orientation.w = math.cos(pose.theta / 2.0)
    return message


def pose_of(message: Any) -> Pose:
    """The planar pose of a ``geometry_msgs/msg/Pose``."""
    return Pose(float(message.position.x), float(message.position.y),
                yaw_of(message.orientation))
