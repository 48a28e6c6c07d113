"""The simulated 2-D laser: rays cast against the true geometry and people's legs, plus noise.

Every beam samples the 2 cm raster once a cell along its length in one
OpenCV remap (a compiled gather; a Python loop per beam would be ~10x slower),
the first solid sample is refined by bisection, and legs are intersected
exactly as circles.
Noise is Gaussian; a share of beams returns a spurious short range instead of
the truth, as feet, reflections and clutter do to real lasers.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np

from homebot.robot import LaserScan, Pose
from homebot.sim.geometry import TRUTH_RESOLUTION, TrueGeometry
from homebot.world import LaserModel

__all__ = ["LEG_RADIUS", "LaserSimulator"]

LEG_RADIUS = 0.06  #: metres
_RANGE_MIN = 0.05
_BISECTIONS = 4


class LaserSimulator:
    """Casts one laser's beams in a world's true geometry.

    Args:
        geometry: the world's true geometry.
        model: beams, field of view, range, noise and spurious share.
        mount: the sensor's pose in the robot's frame.
        rng: draws noise and spurious returns.
    """

    def __init__(self, geometry: TrueGeometry, model: LaserModel, mount: Pose,
                 rng: np.random.Generator) -> None:
        self.geometry = geometry
        self.model = model
        self.mount = mount
        self.rng = rng
        self.angle_min = -model.field_of_view / 2
        self.angle_increment = model.field_of_view / (model.beams - 1)
        self._beam_angles = self.angle_min + self.angle_increment * np.arange(model.beams)
        # Distances along a beam at which the raster is sampled, in cells.
        self._steps = np.arange(1, int(model.range_max / TRUTH_RESOLUTION) + 2, dtype=np.float32)
        # The sample coordinates of one sweep, reused: (beams, samples) in raster cells.
        self._columns = np.empty((model.beams, len(self._steps)), dtype=np.float32)
        self._rows = np.empty_like(self._columns)

    def scan(self, stamp: float, robot: tuple[float, float, float],
             shut_doors: frozenset[str], legs: Sequence[tuple[float, float]]) -> LaserScan:
        """A sweep from the robot's true pose, with these doors shut and these leg centres."""
        x, y, theta = robot
        origin_x = x + self.mount.x * math.cos(theta) - self.mount.y * math.sin(theta)
        origin_y = y + self.mount.x * math.sin(theta) + self.mount.y * math.cos(theta)
        angles = theta + self.mount.theta + self._beam_angles
        directions = np.column_stack((np.cos(angles), np.sin(angles)))
        ranges = self._march((origin_x, origin_y), directions, shut_doors)
        if legs:
            ranges = np.minimum(ranges, _circle_hits((origin_x, origin_y), directions,
                                                     np.asarray(legs, dtype=float), LEG_RADIUS))
        ranges = self._add_noise(ranges)
        return LaserScan(stamp, self.angle_min, self.angle_increment, _RANGE_MIN,
                         self.model.range_max, ranges, self.mount)

    def _march(self, origin: tuple[float, float], directions: np.ndarray,
               shut_doors: frozenset[str]) -> np.ndarray:
        """The first solid sample along each beam, sampled every raster cell, then refined."""
        solid = self.geometry.solid_image(shut_doors)
        raster = self.geometry.raster
        column0 = np.float32((origin[0] - raster.origin[0]) / TRUTH_RESOLUTION - 0.5)
        row0 = np.float32((origin[1] - raster.origin[1]) / TRUTH_RESOLUTION - 0.5)
        steps = self._steps
        columns, rows = self._columns, self._rows
        cos, sin = directions.astype(np.float32).T
        np.multiply(cos[:, None], steps[None, :], out=columns)
        np.multiply(sin[:, None], steps[None, :], out=rows)
        columns += column0
        rows += row0
        # Outside the raster counts as solid: the home ends there.
        samples = cv2.remap(solid, columns, rows, cv2.INTER_NEAREST,
                            borderMode=cv2.BORDER_CONSTANT, borderValue=1)
        first = samples.argmax(axis=1)
        found = samples[np.arange(len(first)), first] == 1
        hit = np.full(len(directions), np.inf)
        far = steps[first[found]] * TRUTH_RESOLUTION
        hit[found] = self._refine(origin, directions[found], far.astype(float), solid)
        hit[hit > self.model.range_max] = np.inf
        return hit

    def _refine(self, origin: tuple[float, float], directions: np.ndarray, far: np.ndarray,
                solid: np.ndarray) -> np.ndarray:
        """Bisect between the last free sample and the first solid one."""
        raster = self.geometry.raster
        near = np.maximum(far - TRUTH_RESOLUTION, 0.0)
        for _ in range(_BISECTIONS):
            middle = (near + far) / 2
            points = origin + directions * middle[:, None]
            column = np.clip(((points[:, 0] - raster.origin[0]) / TRUTH_RESOLUTION).astype(int),
                             0, raster.shape[1] - 1)
            row = np.clip(((points[:, 1] - raster.origin[1]) / TRUTH_RESOLUTION).astype(int),
                          0, raster.shape[0] - 1)
            inside = solid[row, column] == 1
            far = np.where(inside, middle, far)
            near = np.where(inside, near, middle)
        return far

    def _add_noise(self, ranges: np.ndarray) -> np.ndarray:
        model = self.model
        noisy = ranges + self.rng.normal(0.0, model.noise, ranges.shape) if model.noise else ranges
        if model.spurious:
            spurious = self.rng.random(ranges.shape) < model.spurious
            shortest = np.where(np.isfinite(ranges), ranges, model.range_max)
            short = self.rng.uniform(_RANGE_MIN, 1.0, ranges.shape) * shortest
            noisy = np.where(spurious, short, noisy)
        finite = np.isfinite(noisy)
        noisy[finite] = np.clip(noisy[finite], _RANGE_MIN, None)
        return noisy


def _circle_hits(origin: tuple[float, float], directions: np.ndarray, centres: np.ndarray,
                 radius: float) -> np.ndarray:
    """Distance along each ray to the first circle it enters (inf when none)."""
    to_centre = centres[None, :, :] - np.asarray(origin)[None, None, :]
    along = np.einsum("bk,ck->bc", directions, centres - np.asarray(origin))
    squared = np.einsum("ck,ck->c", to_centre[0], to_centre[0])[None, :] - along ** 2
    inside = squared <= radius ** 2
    entry = along - np.sqrt(np.where(inside, radius ** 2 - squared, 0.0))
    entry = np.where(inside & (entry > 0), entry, np.inf)
    nearest: np.ndarray = entry.min(axis=1)
    return nearest
