"""A shut door's leaf, handle and hinge perceived from depth points (Cosero §4.2).

The leaf is the upright plane ahead with the most points (RANSAC over normals near
horizontal). Its extent is the unbroken run of plane points along the plane's horizontal
axis, between the jambs' gaps or steps. The handle is a small cluster of points standing
a few centimetres proud of the leaf, towards the robot, at handle height; it must lie near
one edge of the leaf, and the hinge is the other edge. Nothing here reads the truth: the
input is the head camera's (or any depth sensor's) points in the robot's base frame.

``perceive_door`` returns ``None`` when no leaf of a door's width, or no handle near one
of its edges, is seen; the caller then asks someone to open the door instead.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homebot.perception.tabletop import plane_hypothesis

__all__ = ["SeenDoor", "perceive_door"]

_LEAF_HEIGHTS = (0.25, 1.9)  #: metres above the floor the leaf's plane is fitted over
_HANDLE_HEIGHTS = (0.8, 1.2)  #: metres: where door handles are fitted (DIN 18101: 1.05 m)
_PROUD = (0.025, 0.12)  #: metres a handle stands off the leaf towards the robot
_PLANE_DISTANCE = 0.007  #: metres: on the leaf (a shut leaf stands 2 cm off its wall)
_MAX_TILT = np.radians(8.0)  #: a leaf's normal is within this of horizontal
_BIN = 0.02  #: metres: the leaf's extent is walked in bins this wide
_GAP_BINS = 2  #: this many empty bins in a row end the leaf (a jamb's gap or step)
_WIDTH = (0.55, 1.2)  #: metres: a door leaf's width
_HANDLE_EDGE = 0.25  #: metres: the handle's centre is at most this far in from its edge
_HANDLE_POINTS = 6  #: fewer points proud of the leaf are noise, not a handle
_MIN_LEAF_POINTS = 200
_ITERATIONS = 200
_PLANES_TRIED = 3  #: the largest upright planes searched for a leaf with a handle


@dataclass(frozen=True, slots=True)
class SeenDoor:
    """A door leaf as perceived, in the robot's base frame (x forward, y left, z up).

    Attributes:
        normal: (2,) unit horizontal normal of the leaf, pointing towards the robot.
        hinge: (2,) the hinge edge's foot on the floor.
        latch: (2,) the other (handle-side) edge's foot.
        handle: (3,) the handle's centre.
        width: metres between the two edges.
        handle_end: (3,) the handle's point nearest the latch edge: where a lever turns.
        points: how many depth points lay on the leaf.
    """

    normal: np.ndarray
    hinge: np.ndarray
    latch: np.ndarray
    handle: np.ndarray
    width: float
    points: int
    handle_end: np.ndarray

    @property
    def along(self) -> np.ndarray:
        """(2,) unit horizontal vector along the leaf from the hinge to the latch edge."""
        direction = self.latch - self.hinge
        unit: np.ndarray = direction / np.linalg.norm(direction)
        return unit


def _vertical_plane(points: np.ndarray, rng: np.random.Generator
                    ) -> tuple[np.ndarray, float, np.ndarray] | None:
    """RANSAC for the upright plane ``normal·p + offset = 0`` with the most points.

    Returns ``(normal, offset, inlier_mask)`` with a horizontal unit normal, or ``None``."""
    if len(points) < _MIN_LEAF_POINTS:
        return None
    found = plane_hypothesis(points, _PLANE_DISTANCE, _ITERATIONS, rng,
                             vertical_normal=False, max_tilt=_MAX_TILT)
    if found is None:
        return None
    inliers = np.abs(points @ found[0] + found[1]) < _PLANE_DISTANCE
    if int(inliers.sum()) < _MIN_LEAF_POINTS:
        return None
    # Refit the horizontal normal over the inliers (the principal axes of their footprint).
    footprint = points[inliers, :2]
    centre = footprint.mean(axis=0)
    _, _, axes = np.linalg.svd(footprint - centre, full_matrices=False)
    normal = np.array([axes[1, 0], axes[1, 1], 0.0])
    if float(normal[:2] @ centre) > 0.0:  # point it back towards the robot at the origin
        normal = -normal
    offset = -float(normal[:2] @ centre)
    return normal, offset, np.abs(points @ normal + offset) < _PLANE_DISTANCE


def _runs(coordinates: np.ndarray) -> list[tuple[float, float]]:
    """The unbroken runs of ``coordinates`` (along the leaf's plane), as their two ends.

    Gaps shorter than ``_GAP_BINS`` bins are bridged (depth noise, a missing return)."""
    low = float(coordinates.min())
    bins = np.floor((coordinates - low) / _BIN).astype(np.int64)
    filled = np.flatnonzero(np.bincount(bins) > 0)
    breaks = np.flatnonzero(np.diff(filled) > _GAP_BINS)
    starts = np.concatenate(([filled[0]], filled[breaks + 1]))
    stops = np.concatenate((filled[breaks], [filled[-1]])) + 1
    return [(low + float(start) * _BIN, low + float(stop) * _BIN)
            for start, stop in zip(starts, stops, strict=True)]


def perceive_door(points: np.ndarray, rng: np.random.Generator) -> SeenDoor | None:
    """The door leaf, handle and hinge among (n, 3) base-frame depth ``points``, or ``None``.

    The largest upright planes are tried in turn (the wall round a door is often larger
    than its leaf); the first with a handle near one edge is the door. ``rng`` drives the
    RANSAC (a seeded generator gives the same answer every time).
    """
    height = points[:, 2]
    leaf_band = points[(height > _LEAF_HEIGHTS[0]) & (height < _LEAF_HEIGHTS[1])]
    for _ in range(_PLANES_TRIED):
        plane = _vertical_plane(leaf_band, rng)
        if plane is None:
            return None
        seen = _door_on(points, leaf_band, plane)
        if seen is not None:
            return seen
        leaf_band = leaf_band[~plane[2]]
    return None


def _door_on(points: np.ndarray, leaf_band: np.ndarray,
             plane: tuple[np.ndarray, float, np.ndarray]) -> SeenDoor | None:
    """The door whose leaf is ``plane`` (over ``leaf_band``), if a handle stands off it."""
    normal, offset, on_leaf = plane
    height = points[:, 2]
    along = np.array([-normal[1], normal[0], 0.0])
    # The handle: points proud of the leaf towards the robot, at handle height.
    standoff = points @ normal + offset
    proud = ((standoff > _PROUD[0]) & (standoff < _PROUD[1])
             & (height > _HANDLE_HEIGHTS[0]) & (height < _HANDLE_HEIGHTS[1]))
    proud_along = points[proud] @ along
    for ends in _runs(leaf_band[on_leaf] @ along):
        width = ends[1] - ends[0]
        if not _WIDTH[0] <= width <= _WIDTH[1]:
            continue
        # The handle stands proud in front of this leaf (the wall beside it may stand
        # proud too, but off the leaf's run).
        over = (proud_along > ends[0] + _BIN) & (proud_along < ends[1] - _BIN)
        if int(over.sum()) < _HANDLE_POINTS:
            continue
        handle_points = points[proud][over]
        handle_at = float(np.median(handle_points @ along))
        to_low, to_high = handle_at - ends[0], ends[1] - handle_at
        if min(to_low, to_high) > _HANDLE_EDGE:
            continue  # a protrusion mid-leaf is no handle to open by
        handle = handle_points.mean(axis=0)
        latch_at, hinge_at = (ends[0], ends[1]) if to_low < to_high else (ends[1], ends[0])
        coordinates = handle_points @ along
        end = handle_points[int(np.argmin(coordinates) if latch_at < hinge_at
                                else np.argmax(coordinates))]
        foot = -offset * normal[:2]  # the plane's point nearest the robot
        return SeenDoor(normal=normal[:2].copy(),
                        hinge=foot + hinge_at * along[:2],
                        latch=foot + latch_at * along[:2],
                        handle=handle,
                        width=width,
                        points=int(on_leaf.sum()),
                        handle_end=end.copy())
    return None
