"""Planar angles: wrapping into one turn, and the yaw of a quaternion (REP 103: radians).

numpy is imported by the two functions on arrays only: the language layer wraps single
angles, and a one-shot ``homebot parse`` should not load numpy for that.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

__all__ = [
    "quaternion_from_yaw",
    "wrap_angle",
    "wrap_angles",
    "yaw_from_quaternion",
    "yaw_rotation",
]


def wrap_angle(angle: float) -> float:
    """``angle`` in radians wrapped into [-π, π): the same direction, the shortest turn."""
    return (angle + math.pi) % math.tau - math.pi


def wrap_angles(angles: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """``wrap_angle`` for every angle of an array, elementwise."""
    import numpy as np

    wrapped: npt.NDArray[np.float64] = (np.asarray(angles, dtype=float) + np.pi) % (2 * np.pi) \
        - np.pi
    return wrapped


def quaternion_from_yaw(yaw: float) -> tuple[float, float, float, float]:
    """The unit quaternion ``(w, x, y, z)`` of a turn by ``yaw`` radians about z (up)."""
    return (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))


def yaw_rotation(yaw: float) -> npt.NDArray[np.float64]:
    """The 3×3 rotation matrix of a turn by ``yaw`` radians about z (up); its transpose
    turns back."""
    import numpy as np

    cos, sin = math.cos(yaw), math.sin(yaw)
    return np.array([[cos, -sin, 0.0], [sin, cos, 0.0], [0.0, 0.0, 1.0]])


def yaw_from_quaternion(w: float, x: float, y: float, z: float) -> float:
    """The heading (rotation about z, radians in [-π, π]) of an orientation quaternion."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
