"""Planar geometry at the bottom of the house: ``Pose``, frames, angles, quaternions, rays.

Units and frames follow ROS REP 103: metres, radians, x forward, y left, z up. Every
layer above uses these, as every ROS package uses ``geometry_msgs``; this package
imports nothing of homebot.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.lazy import lazy_exports

if TYPE_CHECKING:
    from homebot.geometry.angles import (
        quaternion_from_yaw,
        wrap_angle,
        wrap_angles,
        yaw_from_quaternion,
        yaw_rotation,
    )
    from homebot.geometry.pose import Pose, from_frame, to_frame
    from homebot.geometry.rays import Point3, Ray, nearest_by_angle, rays_cross_line

__all__ = [
    "Point3",
    "Pose",
    "Ray",
    "from_frame",
    "nearest_by_angle",
    "quaternion_from_yaw",
    "rays_cross_line",
    "to_frame",
    "wrap_angle",
    "wrap_angles",
    "yaw_from_quaternion",
    "yaw_rotation",
]

__getattr__ = lazy_exports(globals())
