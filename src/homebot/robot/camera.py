"""The RGB-D camera's image, as ``sensor_msgs/Image`` + ``CameraInfo`` pairs carry it.

The depth image holds metres along the optical axis (``nan``: no return). The
optical frame follows REP 103's camera convention: z forward, x right, y down;
``camera_pose`` places it in the robot's base frame (x forward, y left, z up).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

__all__ = ["CameraIntrinsics", "RgbdFrame"]


@dataclass(frozen=True, slots=True)
class CameraIntrinsics:
    """A pinhole camera: focal lengths and principal point in pixels, image size."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float

    def rays(self) -> np.ndarray:
        """(height, width, 3) unit-depth rays in the optical frame: (x/z, y/z, 1) per pixel."""
        u = (np.arange(self.width, dtype=np.float64) - self.cx) / self.fx
        v = (np.arange(self.height, dtype=np.float64) - self.cy) / self.fy
        uu, vv = np.meshgrid(u, v)
        return np.stack((uu, vv, np.ones_like(uu)), axis=-1)


@dataclass(frozen=True)
class RgbdFrame:
    """One registered colour and depth image from the head camera.

    Attributes:
        stamp: seconds on the body's clock.
        rgb: (height, width, 3) uint8 colour image.
        depth: (height, width) float32 metres along the optical axis; ``nan`` = no return.
        intrinsics: the pinhole model of both images.
        camera_pose: 4×4 transform from the optical frame to the robot's base frame.
    """

    stamp: float
    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics
    camera_pose: np.ndarray

    def points(self, step: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """The valid depth pixels (every ``step``-th row and column) as (n, 3) points in the
        base frame and their (n, 3) colours."""
        depth = self.depth[::step, ::step]
        valid = np.isfinite(depth)
        rays = _rays(self.intrinsics)[::step, ::step][valid]
        optical = rays * depth[valid][:, None].astype(np.float64)
        rotation, translation = self.camera_pose[:3, :3], self.camera_pose[:3, 3]
        # Written out per axis: ``optical @ rotation.T`` on (n, 3) is ~10x slower (BLAS on a
        # 3-wide matrix), and a frame has ~70k points.
        x, y, z = optical[:, 0], optical[:, 1], optical[:, 2]
        base = np.empty_like(optical)
        for axis in range(3):
            base[:, axis] = (x * rotation[axis, 0] + y * rotation[axis, 1]
                             + z * rotation[axis, 2] + translation[axis])
        return base, self.rgb[::step, ::step][valid]


@functools.lru_cache(maxsize=8)
def _rays(intrinsics: CameraIntrinsics) -> np.ndarray:
    return intrinsics.rays()
