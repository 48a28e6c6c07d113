"""Small conversions between homebot's port types and ROS 2 messages (REP 103 units)."""

from __future__ import annotations

import math
from typing import Any

from homebot.geometry import Pose, quaternion_from_yaw, yaw_from_quaternion
from homebot.transport.types import MessageTypes

__all__ = ["orient", "pose_of", "pose_stamped", "seconds", "stamp", "yaw_of"]


def stamp(types: MessageTypes, time: float) -> Any:
    """A ``builtin_interfaces/msg/Time`` of ``time`` seconds."""
    sec = math.floor(time)
    return types.new("builtin_interfaces/msg/Time", sec=int(sec),
                     nanosec=min(999_999_999, round((time - sec) * 1e9)))


def seconds(time: Any) -> float:
    """Seconds of a ``builtin_interfaces/msg/Time``."""
    return float(time.sec) + float(time.nanosec) * 1e-9


def yaw_of(quaternion: Any) -> float:
    """The heading of a ``geometry_msgs/msg/Quaternion``."""
    return yaw_from_quaternion(quaternion.w, quaternion.x, quaternion.y, quaternion.z)


def orient(quaternion: Any, yaw: float) -> None:
    """Set a ``geometry_msgs/msg/Quaternion`` to a turn by ``yaw`` about z."""
    quaternion.w, quaternion.x, quaternion.y, quaternion.z = quaternion_from_yaw(yaw)


def pose_stamped(types: MessageTypes, pose: Pose, time: float, frame: str = "map") -> Any:
    """A ``geometry_msgs/msg/PoseStamped`` of a planar pose."""
    message = types.new("geometry_msgs/msg/PoseStamped",
                        header=types.new("std_msgs/msg/Header", stamp=stamp(types, time),
                                         frame_id=frame))
    message.pose.position.x, message.pose.position.y = pose.x, pose.y
    orient(message.pose.orientation, pose.theta)
    return message


def pose_of(message: Any) -> Pose:
    """The planar pose of a ``geometry_msgs/msg/Pose``."""
    return Pose(float(message.position.x), float(message.position.y),
                yaw_of(message.orientation))
