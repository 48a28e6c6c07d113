"""ROS 2 over DDS without a ROS installation: homebot's transport (the ``ros`` extra).

``types`` builds ROS 2 message types from the rosbags typestore; ``naming`` holds ROS 2's
topic names and QoS; ``node`` a participant with publishers, subscriptions and services;
``actions`` ROS 2 actions; ``ros_robot`` the Robot port over a team's stack (``RosRobot``);
``sim_server`` a simulated robot on ROS 2 (``homebot sim serve``). Import those modules
after ``require_ros()``: this package itself needs nothing beyond the core.
"""

from __future__ import annotations

import importlib.util

from homebot.errors import TransportError

__all__ = ["require_ros"]


def require_ros() -> None:
    """Raise a clear error when the ``ros`` extra (cyclonedds, rosbags) is not installed."""
    missing = [name for name in ("cyclonedds", "rosbags")
               if importlib.util.find_spec(name) is None]
    if missing:
        raise TransportError(f"ROS 2 needs the 'ros' extra ({', '.join(missing)} missing): "
                           "pip install 'homebot[ros]'")
