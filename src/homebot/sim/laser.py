"""The simulated 2-D laser: rays cast against the true geometry and people's legs, plus noise.

Every beam samples the 2 cm raster once a cell along its length until its
first solid sample (a numba kernel, ``_march_beams``: each beam stops at its
hit instead of sampling its whole range, and passes over samples that are free
for sure, far from anything solid), which is refined by bisection; legs
are intersected exactly as circles.
Noise is Gaussian; a share of beams returns a spurious short range instead of
the truth, as feet, reflections and clutter do to real lasers.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy import ndimage

from homebot.compiled import compiled
from homebot.geometry import Pose
from homebot.robot import LaserScan
from homebot.sim.geometry import TRUTH_RESOLUTION, TrueGeometry
from homebot.world import LaserModel

__all__ = ["LEG_RADIUS", "LaserSimulator"]

LEG_RADIUS = 0.06  #: metres
_RANGE_MIN = 0.05
_BISECTIONS = 4


@compiled
def _march_beams(solid: np.ndarray, free_run: np.ndarray, column0: np.float32,
                 row0: np.float32, cos: np.ndarray, sin: np.ndarray, steps: np.ndarray,
                 directions: np.ndarray, origin_x: float, origin_y: float, raster_x: float,
                 raster_y: float, cell: float, range_max: float,
                 bisections: int) -> np.ndarray:
    """Per beam, the range to its first solid sample (inf: none within ``range_max``).

    Samples lie ``steps`` cells along each beam from (``column0``, ``row0``),
    computed in float32 and rounded to the nearest cell; outside the raster
    counts as solid (the home ends there). ``free_run`` says, per free cell, how
    many samples after one that falls in it are free for sure (see
    ``_free_runs``): those are not looked at. The hit is then refined by
    bisecting between the last free sample and the first solid one.
    """
    rows, columns = solid.shape
    hits = np.full(len(cos), np.inf)
    count = len(steps)
    for beam in range(len(cos)):
        far = -1.0
        i = 0
        while i < count:
            step = steps[i]
            column = np.rint(cos[beam] * step + column0)
            row = np.rint(sin[beam] * step + row0)
            if not (0 <= column < columns and 0 <= row < rows) or \
                    solid[int(row), int(column)] == 1:
                far = float(step * np.float32(cell))
                break
            i += 1 + free_run[int(row), int(column)]
        if far < 0.0:
            continue
        near = max(far - cell, 0.0)
        dx, dy = directions[beam, 0], directions[beam, 1]
        for _ in range(bisections):
            middle = (near + far) / 2
            c = min(max(int((origin_x + dx * middle - raster_x) / cell), 0), columns - 1)
            r = min(max(int((origin_y + dy * middle - raster_y) / cell), 0), rows - 1)
            if solid[r, c] == 1:
                far = middle
            else:
                near = middle
        if far <= range_max:
            hits[beam] = far
    return hits


def _free_runs(solid: np.ndarray) -> np.ndarray:
    """Per free cell, how many further samples of a beam after one in it are free for sure.

    A sample is its point rounded to the nearest cell, so within half a diagonal
    (0.71 cells) of it; the samples are one cell apart along the beam. The
    sample k steps on is then at most k + 1.42 cells from this one's cell, and
    free while that is less than the distance to the nearest solid cell (or
    the raster's edge, beyond which all is solid).
    """
    free = np.pad(solid == 0, 1, constant_values=False)
    distance = ndimage.distance_transform_edt(free)[1:-1, 1:-1]
    runs: np.ndarray = np.maximum(np.ceil(distance - 1.42 - 1e-3) - 1, 0).astype(np.int32)
    return runs


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
        self._free_runs: dict[tuple[frozenset[str], frozenset[str]], np.ndarray] = {}

    def scan(self, stamp: float, robot: tuple[float, float, float],
             shut_doors: frozenset[str], legs: Sequence[tuple[float, float]],
             swung_back: frozenset[str] = frozenset()) -> LaserScan:
        """A sweep from the robot's true pose, with these doors shut, these leaves swung
        back against the wall and these leg centres."""
        x, y, theta = robot
        origin_x, origin_y = Pose(x, y, theta).apply(self.mount.x, self.mount.y)
        angles = theta + self.mount.theta + self._beam_angles
        directions = np.column_stack((np.cos(angles), np.sin(angles)))
        ranges = self._march((origin_x, origin_y), directions, shut_doors, swung_back)
        if legs:
            ranges = np.minimum(ranges, _circle_hits((origin_x, origin_y), directions,
                                                     np.asarray(legs, dtype=float), LEG_RADIUS))
        ranges = self._add_noise(ranges)
        return LaserScan(stamp, self.angle_min, self.angle_increment, _RANGE_MIN,
                         self.model.range_max, ranges, self.mount)

    def _march(self, origin: tuple[float, float], directions: np.ndarray,
               shut_doors: frozenset[str], swung_back: frozenset[str]) -> np.ndarray:
        """The first solid sample along each beam, sampled every raster cell, then refined."""
        solid = self.geometry.solid_image(shut_doors, swung_back)
        key = (shut_doors, swung_back)
        if key not in self._free_runs:
            self._free_runs[key] = _free_runs(solid)
        raster = self.geometry.raster
        column0 = np.float32((origin[0] - raster.origin[0]) / TRUTH_RESOLUTION - 0.5)
        row0 = np.float32((origin[1] - raster.origin[1]) / TRUTH_RESOLUTION - 0.5)
        cos, sin = directions.astype(np.float32).T
        hits: np.ndarray = _march_beams(
            solid, self._free_runs[key], column0, row0, np.ascontiguousarray(cos),
            np.ascontiguousarray(sin), self._steps, np.ascontiguousarray(directions),
            origin[0], origin[1], raster.origin[0], raster.origin[1], TRUTH_RESOLUTION,
            self.model.range_max, _BISECTIONS)
        return hits

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
