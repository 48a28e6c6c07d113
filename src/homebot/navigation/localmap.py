"""What a local controller sees: a robot-centred grid from one laser scan, and the path ahead.

CAESAR's collision avoidance uses only a local map built from the current
laser reading, so it works among things the static map does not hold (people,
a chair moved). ``LocalGrid`` rasterises the scan's returns into a square
grid round the robot (base_link frame) and keeps, per cell, the clearance:
the distance to the nearest return. Growing obstacles by a radius (and by a
margin that rises with speed) is then a comparison with that clearance. A
cell's clearance is measured from its centre, so it may be off by a few
centimetres at a point in the cell; where that matters (near the margin), the
returns themselves are kept too, bucketed, for the exact distance
(``exact_clearance``, and ``motion_search.clearance_near`` in the search).
``lookahead`` picks the point of the global path the controller steers for.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from homebot.errors import LocalPlannerError
from homebot.geometry import Pose, to_frame
from homebot.robot import DriveKind, LaserScan, Twist, VelocityLimits

_CLUSTER_JUMP = 0.1  #: metres: a bigger range step between beams starts a new cluster
_SMALL = 0.2  #: metres: clusters narrower than this (and in front of their surroundings) are small
_PAIR = 0.4  #: metres: two small clusters this close are a pair of legs
_HIDDEN_BEAMS = 3  #: a leg half hidden behind the other shows at least this many returns
_BUCKET = 0.25  #: metres: side of the buckets the returns are kept in for exact distances

__all__ = [
    "LocalController",
    "LocalGrid",
    "check_request",
    "lookahead",
    "visible_lookahead",
]


class LocalController(Protocol):
    """A local controller (Nav2's controller server): velocity from the scan and the path."""

    def plan(self, pose: Pose, velocity: Twist, scan: LaserScan,
             path: Sequence[tuple[float, float]], limits: VelocityLimits, drive: DriveKind,
             radius: float) -> Twist:
        """The next command.

        Args:
            pose: the localisation estimate, map frame.
            velocity: the base's current velocity (odometry), robot frame.
            scan: the latest laser sweep.
            path: the global path's waypoints (map frame), the goal last.
            limits: the base's velocity and acceleration limits.
            drive: omnidirectional or differential.
            radius: the base's footprint radius (metres).

        Returns:
            The velocity to command now, robot frame, within ``limits`` and reachable
            from ``velocity`` in one control period.
        """
        ...


def check_request(path: Sequence[tuple[float, float]], radius: float) -> None:
    """Raise ``LocalPlannerError`` for a path or radius no controller can use."""
    if len(path) == 0:
        raise LocalPlannerError("the path is empty; give at least the goal as one waypoint")
    if not (math.isfinite(radius) and radius > 0):
        raise LocalPlannerError(f"the robot radius must be a positive number of metres, "
                                f"not {radius!r}")
    for point in path:
        if len(point) != 2 or not all(math.isfinite(value) for value in point):
            raise LocalPlannerError(f"path waypoint {point!r} is not a finite (x, y) point")


@dataclass(frozen=True)
class LocalGrid:
    """A square grid centred on the robot (base_link frame), built from one scan.

    ``clearance[row, column]`` is the distance in metres from the cell's centre
    to the nearest laser return (rows along y, columns along x). Outside the
    grid nothing is known; ``clearance_at`` reports ``outside`` there.
    ``returns`` holds the returns in the grid as rows (x, y, how much nearer
    they count: the leg margin for legs, else 0; 1 for a wall's or furniture's,
    a cluster wider than a leg, else 0), sorted by bucket (``bucket``
    metres square, ``per_side`` buckets a side from −``half_size``), bucket k's
    being rows ``starts[k]:starts[k + 1]``.
    """

    resolution: float
    half_size: float
    clearance: np.ndarray
    outside: float = 10.0
    returns: np.ndarray = field(default_factory=lambda: np.zeros((0, 4)))
    starts: np.ndarray = field(default_factory=lambda: np.zeros(2, dtype=np.int64))
    bucket: float = _BUCKET
    per_side: int = 1
    leg_margin: float = 0.0

    @classmethod
    def from_scan(cls, scan: LaserScan, size: float = 4.0, resolution: float = 0.05,
                  leg_margin: float = 0.0) -> LocalGrid:
        """Rasterise the scan's returns into a ``size`` × ``size`` metre grid.

        The robot sits in the middle of the centre cell (the cell count is odd).
        Each cell's clearance is the exact distance from its centre to the return
        kept in the nearest occupied cell, so it is off by at most the distance
        between two returns in neighbouring cells, not by whole cells. With a
        ``leg_margin``, returns in pairs of small free-standing clusters (legs:
        the person above them is wider) count that much nearer.
        """
        from homebot.navigation import motion_search  # numba: only once a controller plans

        cells = round(size / resolution) | 1
        half = cells * resolution / 2
        points, small, wide = _returns(scan)
        clearance = _clearance(points, cells, half, resolution)
        if leg_margin > 0 and small.any():
            legs = _clearance(points[small], cells, half, resolution) - leg_margin
            clearance = np.minimum(clearance, np.maximum(legs, 0.0))
        nearer = np.where(small, leg_margin, 0.0) if leg_margin > 0 else np.zeros(len(points))
        per_side = max(math.ceil(2 * half / _BUCKET), 1)
        returns, starts = motion_search.bucketed(points, nearer, wide, half, _BUCKET,
                                                 per_side)
        return cls(resolution, half, np.asarray(clearance, dtype=float), returns=returns,
                   starts=starts, bucket=_BUCKET, per_side=per_side,
                   leg_margin=max(leg_margin, 0.0))

    @property
    def cells(self) -> int:
        return int(self.clearance.shape[0])

    def index(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(rows, columns) of the cells nearest to robot-frame points (clamped into the grid)."""
        last = self.cells - 1
        scale = 1.0 / self.resolution
        columns = np.minimum(np.maximum((x + self.half_size) * scale, 0), last).astype(np.intp)
        rows = np.minimum(np.maximum((y + self.half_size) * scale, 0), last).astype(np.intp)
        return rows, columns

    def clearance_at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Clearance at robot-frame points (``outside`` beyond the grid)."""
        padded = self.padded
        last = self.cells + 1
        scale = 1.0 / self.resolution
        columns = np.minimum(np.maximum((x + self.half_size) * scale + 1, 0), last).astype(np.intp)
        rows = np.minimum(np.maximum((y + self.half_size) * scale + 1, 0), last).astype(np.intp)
        values: np.ndarray = padded[rows, columns]
        return values

    def exact_clearance(self, x: float, y: float, farther: float = 0.0) -> float:
        """The distance from a robot-frame point to the nearest return (legs counting
        ``leg_margin`` nearer, walls and furniture ``farther``; ``outside`` when the grid
        holds none)."""
        if not len(self.returns):
            return self.outside
        gaps = np.hypot(self.returns[:, 0] - x, self.returns[:, 1] - y) - self.returns[:, 2] \
            + farther * self.returns[:, 3]
        return float(gaps.min())

    @property
    def slack(self) -> float:
        """How far a cell's clearance may overstate the exact one anywhere in the cell: half
        a diagonal from its centre, and twice that from taking the nearest occupied cell's
        kept return for the nearest return."""
        return 3 * self.resolution * math.sqrt(0.5)

    @functools.cached_property
    def padded(self) -> np.ndarray:
        """The clearance with a one-cell border of ``outside`` (nothing known there)."""
        padded: np.ndarray = np.pad(self.clearance, 1, constant_values=self.outside)
        return padded

    def centre_of(self, row: int, column: int) -> tuple[float, float]:
        return ((column + 0.5) * self.resolution - self.half_size,
                (row + 0.5) * self.resolution - self.half_size)

    def distance_field(self, target: tuple[float, float], grown: float,
                       pool: int = 2, speed: tuple[float, float] | None = None) -> np.ndarray:
        """Path length (metres) from every cell to ``target`` among cells clearer than ``grown``.

        CAESAR's first local search (by length), done as one Dijkstra sweep out
        from the target so that every motion the second search tries can look
        up its remaining distance. The sweep runs on cells ``pool`` times coarser
        (a coarse cell is clear when any of its cells is), which is plenty for a
        heuristic. A target inside grown obstacles moves to the nearest clear
        cell; cells that are not clear get the field of their nearest clear cell
        plus the way to it (so the robot can leave them). With ``speed`` =
        (speed margin, top speed), Cosero's collision-aware speed limit: a cell
        whose clearance beyond ``grown`` is c may be crossed at c / margin at
        most (and at 0.05 m/s at least), a step costs its length times how many
        times slower than top speed that is, and the field is in metres at top
        speed: time × top speed. Compiled (``motion_search.coarse_field``).
        """
        from homebot.navigation import motion_search  # numba: only once a controller plans

        resolution = self.resolution * pool
        margin, top = speed if speed is not None else (1.0, 0.0)
        coarse, everywhere = motion_search.coarse_field(
            self.clearance, grown, pool, (target[0] + self.half_size) / resolution,
            (target[1] + self.half_size) / resolution, max(margin, 1e-6), top, resolution)
        if not everywhere:
            coarse = motion_search.fill_unreached(coarse, resolution)
        field: np.ndarray = motion_search.expand(coarse, pool, self.cells)
        return field


def _returns(scan: LaserScan) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The scan's returns (robot frame), which belong to legs (pairs of small clusters in
    front of what is beside them) and which to wide clusters (walls, furniture); see
    ``motion_search.classify_returns``."""
    from homebot.navigation import motion_search  # numba: only once a controller plans

    keep = scan.valid()
    ranges = np.where(keep, scan.ranges, np.nan)
    angles = scan.angles() + scan.mount.theta
    xs = scan.mount.x + ranges * np.cos(angles)
    ys = scan.mount.y + ranges * np.sin(angles)
    small, wide = motion_search.classify_returns(ranges, xs, ys, _CLUSTER_JUMP, _SMALL, _PAIR,
                                                 _HIDDEN_BEAMS)
    return np.column_stack((xs[keep], ys[keep])), small[keep], wide[keep]


def _clearance(points: np.ndarray, cells: int, half: float, resolution: float) -> np.ndarray:
    """Per cell, the distance from its centre to the return kept in the nearest occupied cell."""
    from homebot.navigation import motion_search  # numba: only once a controller plans

    clearance: np.ndarray = motion_search.clearance_grid(points, cells, half, resolution, 10.0)
    return clearance


def lookahead(pose: Pose, path: Sequence[tuple[float, float]],
              distance: float) -> tuple[tuple[float, float], bool]:
    """The point ``distance`` metres along ``path`` past the point nearest the robot.

    Returns the point in the robot's frame and whether it is the path's end
    (the goal, where the robot must stop rather than pass through).
    """
    points = to_frame(pose, np.asarray(path, dtype=float).reshape(-1, 2))
    if len(points) == 1:
        goal = (float(points[0, 0]), float(points[0, 1]))
        return goal, True
    starts, ends = points[:-1], points[1:]
    segment = ends - starts
    lengths = np.hypot(segment[:, 0], segment[:, 1])
    safe = np.where(lengths > 0, lengths, 1.0)
    along = np.clip(-(starts * segment).sum(axis=1) / safe**2, 0.0, 1.0)
    nearest = starts + along[:, None] * segment
    index = int(np.argmin(np.hypot(nearest[:, 0], nearest[:, 1])))
    left = distance
    position = along[index] * lengths[index]
    for i in range(index, len(segment)):
        remaining = lengths[i] - (position if i == index else 0.0)
        if remaining >= left:
            fraction = ((position if i == index else 0.0) + left) / safe[i]
            point = starts[i] + fraction * segment[i]
            return (float(point[0]), float(point[1])), False
        left -= remaining
    return (float(points[-1, 0]), float(points[-1, 1])), True


def visible_lookahead(grid: LocalGrid, field: np.ndarray, distance: float,
                      clearance: float) -> tuple[float, float]:
    """The carrot: the furthest point of the local path (down ``field``) in straight sight.

    The local path runs from the robot's cell down the distance field (stage 2's
    first search, by length) for at most ``distance`` metres; the carrot is its
    furthest point whose straight line from the robot keeps ``clearance`` from
    every return (or its first step, when none does).
    """
    rows, columns = grid.index(np.zeros(1), np.zeros(1))
    row, column = int(rows[0]), int(columns[0])
    last = grid.cells - 1
    points: list[tuple[float, float]] = []
    travelled = 0.0
    while travelled < distance:
        best = (float(field[row, column]), row, column)
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                r, c = row + dr, column + dc
                if 0 <= r <= last and 0 <= c <= last and field[r, c] < best[0]:
                    best = (float(field[r, c]), r, c)
        if best[1:] == (row, column):
            break
        travelled += grid.resolution * math.hypot(best[1] - row, best[2] - column)
        row, column = best[1], best[2]
        points.append(grid.centre_of(row, column))
    if not points:
        return (0.0, 0.0)
    for point in reversed(points):
        samples = max(int(math.hypot(*point) / (grid.resolution / 2)), 1)
        t = np.linspace(0.0, 1.0, samples + 1)[1:]
        if np.all(grid.clearance_at(t * point[0], t * point[1]) >= clearance):
            return point
    return points[0]
