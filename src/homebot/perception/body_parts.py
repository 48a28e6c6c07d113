"""A person's head, shoulder, elbow and hand from the head camera's depth image (Cosero §7.1.3).

Cosero starts from the face, segments the person in the depth image, then the
trunk and the arms, and finds head, shoulder, elbow and hand. Here, for one RGB-D
frame and where the person stands (the leg tracker's or the camera's body
position, map frame):

1. Every depth pixel becomes a map-frame point. Points within ``_REACH`` of the
   person, above the floor, are the candidates; they fall into connected regions
   on a grid of ``_VOXEL`` cubes (``scipy.ndimage.label``). The person is the
   regions that fill the column where they were said to stand (head, trunk and legs
   may come apart where one overhangs the next), and regions of an arm's size that
   reach their trunk's side by the shoulders: a table, a counter or a wall
   beside them, a hand's breadth away, is not.
2. The trunk's axis: the median of the points near it, set back by the depth a
   round trunk's seen surface lies in front of its axis, twice. The head is the
   top of the points round the axis; the shoulders lie a fixed share of a body
   below the head's top (anthropometry: about 0.19 of the stature, 0.33 m).
3. The arms: the person's points well out of the trunk's column (or above the
   trunk, beside the head), each connected piece given to the shoulder it comes
   nearest: the person's left or right (a gesturing person faces the robot, so
   their shoulders lie across the line to it).
   The hand is the far end of the arm, followed along its points from the
   shoulder (shortest paths on a grid, ``scipy.sparse.csgraph``), set back by a
   hand's radius; the elbow lies an upper arm's length along it.

``arm_track`` does this over a burst of frames and keeps the arm held out in
most of them; it gives the (frames, 4, 3) keypoints ``perception.gestures``
classifies. An arm that nowhere leaves the trunk hangs: its keypoints say so.
Nothing here reads the simulator: only the frames and the robot's own pose.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra
from scipy.spatial import cKDTree

from homebot.geometry import Pose
from homebot.robot import CameraIntrinsics, RgbdFrame

__all__ = ["BodyParts", "arm_track", "body_parts", "looking_tilt"]

_REACH = 1.0  #: metres from the person's axis an arm can reach
_FLOOR = 0.25  #: metres: points lower are the floor's or the feet's
_VOXEL = 0.04  #: metres: the grid the person's points are joined on
_CORE = 0.25  #: metres from the axis: the trunk's column
_SAID = 0.35  #: metres round where the person was said to stand that their trunk fills ...
_SAID_LOW = 1.0  #: ... above this height (metres; over tables and counters, below a seated head)
_SHARE = 0.05  #: of those points a region of the person's holds at least
_SEEN_DEPTH = 0.13  #: metres from a trunk's seen surface back to its axis
_HEAD_COLUMN = 0.14  #: metres from the axis that the head's points lie within
_HEAD_CENTRE = 0.12  #: metres below the head's top: the eyes, the head's keypoint
_SHOULDER_DROP = 0.33  #: metres from the head's top down to the shoulders
_TRUNK_TOP = 0.17  #: metres below the head's top where the trunk has surely ended
_OUT_OF_TRUNK = 0.28  #: metres from the axis: beyond the trunk's surface
_BESIDE_HEAD = 0.16  #: metres from the axis: beside the head, above the trunk
_ARM_DROP = 0.55  #: metres below the shoulder an arm held out can reach down to
_MIN_ARM = 12  #: pixels of an arm held out
_SHOULDER_ZONE = 0.25  #: metres above or below the shoulders where an arm leaves the trunk
_ARM_SIZE = 0.85  #: metres: the most an arm's points span
_ARM_OUT = 0.3  #: metres from the axis an arm held out reaches beyond ...
_ARM_UP = 0.1  #: ... or to this below the head's top (the trunk's rim does neither)
_ARM_CELL = 0.03  #: metres: the grid an arm's points are joined on, to follow it to the hand
_UPPER_ARM = 0.30  #: metres: shoulder to elbow
_HAND_RADIUS = 0.05  #: metres
_SHOULDER_WIDTH = 0.19  #: metres from the axis to a shoulder joint
_MIN_HEAD = 8  #: pixels of a head
_EDGE_ROWS = 2  #: rows at the picture's top: a head reaching them is cut off
_TALL = 2.0  #: metres: the top of a tall person's raised hand, seen from the front
_GAZE_HEIGHT = 1.55  #: metres: where the head looks on a person
_CAMERA_HEIGHT = 1.3  #: metres: the head camera above the floor (a robot profile's)


@dataclass(frozen=True)
class BodyParts:
    """A person as one depth frame shows them (map frame, metres).

    Attributes:
        axis: where their trunk's vertical axis stands.
        head: the head's keypoint (between the eyes).
        shoulders: each side's shoulder joint ("left", "right": the person's own).
        arms: each arm held out of the trunk: (elbow, hand).
    """

    axis: np.ndarray
    head: np.ndarray
    shoulders: dict[str, np.ndarray]
    arms: dict[str, tuple[np.ndarray, np.ndarray]]

    def keypoints(self, side: str) -> np.ndarray:
        """Head, shoulder, elbow, hand (4, 3) of the ``side`` arm: held out as seen, else
        hanging by the trunk."""
        shoulder = self.shoulders[side]
        if side in self.arms:
            elbow, hand = self.arms[side]
        else:
            elbow = shoulder - np.array([0.0, 0.0, _UPPER_ARM])
            hand = elbow - np.array([0.0, 0.0, _UPPER_ARM])
        return np.stack((self.head, shoulder, elbow, hand))


def body_parts(frame: RgbdFrame, pose: Pose, person: tuple[float, float]) -> BodyParts | None:
    """The person standing or sitting near ``person`` (map frame) in ``frame``, taken with
    the robot at ``pose`` (its estimate): None when the frame shows no one there."""
    points, valid = _map_points(frame, pose)
    robot = np.array([pose.x, pose.y])
    centre = np.asarray(person, dtype=float)
    flat = points[..., :2] - centre
    near = valid & (np.einsum("...i,...i->...", flat, flat) < (_REACH + 0.3) ** 2) & (
        points[..., 2] > _FLOOR)
    if np.count_nonzero(near) < _MIN_ARM:
        return None
    # the person: the region with most points in the column where they were said to stand
    regions = np.zeros(near.shape, dtype=np.int32)
    regions[near] = _regions(points[near])
    said = near & (np.einsum("...i,...i->...", flat, flat) < _SAID ** 2) & (
        points[..., 2] > _SAID_LOW)
    if np.count_nonzero(said) < _MIN_HEAD:
        return None
    # head, trunk and legs may part on the grid where one overhangs the next
    counts = np.bincount(regions[said])
    mine = np.flatnonzero(counts >= max(_MIN_HEAD, _SHARE * np.count_nonzero(said)))
    person_mask = near & np.isin(regions, mine)
    axis = _axis(points[person_mask], centre, robot)
    if axis is None:
        return None
    offset = points[..., :2] - axis
    distance = np.hypot(offset[..., 0], offset[..., 1])
    person_mask &= distance < _REACH
    core = person_mask & (distance < _CORE)
    column = core & (distance < _HEAD_COLUMN)
    if np.count_nonzero(column) < _MIN_HEAD:
        return None
    top = float(np.quantile(points[column][:, 2], 0.99))
    rows = np.nonzero(column)[0]
    if rows.min() <= _EDGE_ROWS and np.any(points[column][rows <= _EDGE_ROWS, 2] > top - 0.05):
        return None  # the head runs out of the picture: its top, and so the shoulders, unknown
    shoulder_height = top - _SHOULDER_DROP
    person_mask |= _attached(points, regions, near & ~person_mask, distance, shoulder_height)
    facing = robot - axis
    facing /= max(float(np.linalg.norm(facing)), 1e-9)
    right = np.array([facing[1], -facing[0]])  # facing the robot, their right is its left
    head_points = points[column & (points[..., 2] > top - 2 * _HEAD_CENTRE)]
    if len(head_points) < _MIN_HEAD:
        return None
    head_xy = head_points[:, :2].mean(axis=0) - facing * _HEAD_CENTRE * 2 / 3
    head = np.array([head_xy[0], head_xy[1], top - _HEAD_CENTRE])
    shoulders = {side: np.array([*(axis + sign * _SHOULDER_WIDTH * right), shoulder_height])
                 for side, sign in (("right", 1.0), ("left", -1.0))}
    z = points[..., 2]
    # beside the head: measured from the head's own middle, which the trunk's axis may miss
    from_head = np.hypot(points[..., 0] - head_xy[0], points[..., 1] - head_xy[1])
    out = person_mask & (z > shoulder_height - _ARM_DROP) & (
        (distance > _OUT_OF_TRUNK) | ((z > top - _TRUNK_TOP) & (from_head > _BESIDE_HEAD)))
    arm_points = points[out]
    arms = {}
    for side, chosen in _by_shoulder(arm_points, shoulders).items():
        if len(chosen) < _MIN_ARM:
            continue
        # an arm reaches well out of the trunk or over it; the trunk's rim does neither
        out_far = float(np.max(np.hypot(*(chosen[:, :2] - axis).T))) >= _ARM_OUT
        if out_far or float(chosen[:, 2].max()) >= top - _ARM_UP:
            arms[side] = _arm(chosen, shoulders[side], facing)
    return BodyParts(axis, head, shoulders, arms)


def arm_track(frames: Sequence[RgbdFrame], poses: Sequence[Pose],
              person: tuple[float, float]) -> np.ndarray | None:
    """Keypoints (n, 4, 3), map frame: head, shoulder, elbow, hand of the arm the person
    holds out in most of ``frames`` (each taken from the pose of the same index in
    ``poses``), over the frames it was seen in; their hanging right arm when neither is
    held out; None when no frame shows the person near ``person``."""
    if len(frames) != len(poses):
        raise ValueError(f"{len(frames)} frames but {len(poses)} poses; one pose a frame")
    seen = [parts for frame, pose in zip(frames, poses, strict=True)
            if (parts := body_parts(frame, pose, person)) is not None]
    if not seen:
        return None
    counts = {side: sum(side in parts.arms for parts in seen) for side in ("right", "left")}
    reach = {side: sum(float(np.linalg.norm(parts.arms[side][1] - parts.shoulders[side]))
                       for parts in seen if side in parts.arms) for side in counts}
    side = max(counts, key=lambda name: (counts[name], reach[name]))
    if counts[side] == 0:
        return np.stack([parts.keypoints("right") for parts in seen])
    return np.stack([parts.keypoints(side) for parts in seen if side in parts.arms])


def _map_points(frame: RgbdFrame, pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Every pixel's point in the map frame (h, w, 3) and which pixels have a return."""
    depth = frame.depth.astype(np.float64)
    valid = np.isfinite(depth)
    optical = frame.intrinsics.rays() * np.nan_to_num(depth)[..., None]
    base = optical @ frame.camera_pose[:3, :3].T + frame.camera_pose[:3, 3]
    cos, sin = math.cos(pose.theta), math.sin(pose.theta)
    points = np.empty_like(base)
    points[..., 0] = pose.x + cos * base[..., 0] - sin * base[..., 1]
    points[..., 1] = pose.y + sin * base[..., 0] + cos * base[..., 1]
    points[..., 2] = base[..., 2]
    return points, valid


def _axis(points: np.ndarray, start: np.ndarray, robot: np.ndarray) -> np.ndarray | None:
    """The trunk's axis near ``start``: the median of the nearby points, set back from
    the robot by the depth of a trunk's seen surface (twice, narrowing)."""
    axis = start
    for radius in (0.45, 0.3):
        offset = points[:, :2] - axis
        close = points[np.einsum("ij,ij->i", offset, offset) < radius ** 2]
        if len(close) < _MIN_HEAD:
            return None
        middle = np.median(close[:, :2], axis=0)
        away = middle - robot
        axis = middle + _SEEN_DEPTH * away / max(float(np.linalg.norm(away)), 1e-9)
    return axis


def _regions(points: np.ndarray) -> np.ndarray:
    """Each point's connected region (from 1) on a grid of ``_VOXEL`` cubes, neighbours
    touching at faces, edges or corners."""
    cells = np.floor((points - points.min(axis=0)) / _VOXEL).astype(np.intp)
    grid = np.zeros(tuple(cells.max(axis=0) + 1), dtype=bool)
    grid[cells[:, 0], cells[:, 1], cells[:, 2]] = True
    labels, _ = ndimage.label(grid, structure=np.ones((3, 3, 3)))
    regions: np.ndarray = labels[cells[:, 0], cells[:, 1], cells[:, 2]]
    return regions


def _by_shoulder(points: np.ndarray, shoulders: dict[str, np.ndarray]
                 ) -> dict[str, np.ndarray]:
    """The arm points of each side: each connected piece goes to the shoulder it comes
    nearest (a hand swept across the body stays with its own shoulder)."""
    pieces: dict[str, list[np.ndarray]] = {side: [] for side in shoulders}
    if len(points) == 0:
        return {side: np.zeros((0, 3)) for side in shoulders}
    labels = _regions(points)
    reach = {side: np.linalg.norm(points - shoulder, axis=1)
             for side, shoulder in shoulders.items()}
    for label in np.unique(labels):
        mine = labels == label
        side = min(shoulders, key=lambda name: float(reach[name][mine].min()))
        pieces[side].append(points[mine])
    return {side: np.concatenate(parts) if parts else np.zeros((0, 3))
            for side, parts in pieces.items()}


def _attached(points: np.ndarray, regions: np.ndarray, others: np.ndarray,
              distance: np.ndarray, shoulder_height: float) -> np.ndarray:
    """The pixels of regions among ``others`` that are an arm apart from the trunk on the
    grid: they reach the trunk's side near the shoulders, and are no bigger than an arm
    (a wall or a cupboard beside the person is)."""
    z = points[..., 2]
    touching = others & (distance < _OUT_OF_TRUNK + _VOXEL) & (
        np.abs(z - shoulder_height) < _SHOULDER_ZONE)
    attached = np.zeros(others.shape, dtype=bool)
    for region in np.unique(regions[touching]):
        pixels = others & (regions == region)
        extent = np.ptp(points[pixels], axis=0)
        if float(np.linalg.norm(extent)) <= _ARM_SIZE and \
                float(z[pixels].min()) > shoulder_height - _ARM_DROP - _HAND_RADIUS:
            attached |= pixels
    return attached


def _arm(points: np.ndarray, shoulder: np.ndarray, facing: np.ndarray
         ) -> tuple[np.ndarray, np.ndarray]:
    """Elbow and hand of an arm's points held out from ``shoulder``: the hand is the far
    end along the arm (a bent arm's hand may lie nearer the shoulder than its elbow),
    the elbow an upper arm's length along it."""
    cells, inverse = np.unique(np.floor(points / _ARM_CELL).astype(np.intp), axis=0,
                               return_inverse=True)
    inverse = inverse.reshape(-1)
    centres = np.zeros((len(cells), 3))
    np.add.at(centres, inverse, points)
    centres /= np.bincount(inverse, minlength=len(cells))[:, None]
    pairs = cKDTree(centres).query_pairs(1.8 * _ARM_CELL, output_type="ndarray")
    lengths = np.linalg.norm(centres[pairs[:, 0]] - centres[pairs[:, 1]], axis=1)
    graph = coo_matrix((lengths, (pairs[:, 0], pairs[:, 1])), shape=(len(cells),) * 2)
    from_shoulder = np.linalg.norm(centres - shoulder, axis=1)
    start = int(np.argmin(from_shoulder))
    along = dijkstra(graph.tocsr(), directed=False, indices=[start])[0] + from_shoulder[start]
    reached = np.isfinite(along)
    end = float(along[reached].max())
    tip = centres[reached & (along >= end - _HAND_RADIUS)].mean(axis=0)
    before = centres[reached & (along >= end - 3 * _HAND_RADIUS) & (along < end - _HAND_RADIUS)]
    base = before.mean(axis=0) if len(before) else shoulder
    pointing = tip - base
    pointing /= max(float(np.linalg.norm(pointing)), 1e-9)
    back = np.array([-facing[0], -facing[1], 0.0])  # the seen surface lies towards the robot
    # the points at the far end lie half a hand past its middle, on the side seen
    hand = tip - 0.5 * _HAND_RADIUS * pointing + 0.5 * _HAND_RADIUS * back
    middle = reached & (np.abs(along - _UPPER_ARM) < _ARM_CELL * 2)
    elbow = centres[middle].mean(axis=0) if np.any(middle) else (shoulder + hand) / 2
    return elbow, hand


def looking_tilt(distance: float, intrinsics: CameraIntrinsics) -> float:
    """The head's tilt (radians, down positive) that keeps a person ``distance`` metres
    away in the picture of a camera with ``intrinsics``: level with a tall person's chin,
    or higher when they stand so near that a raised hand would leave the picture (Cosero
    adjusts its gaze to keep the hand and the head in the image)."""
    half_view = math.atan2(intrinsics.cy, intrinsics.fy)
    front = max(distance - _SEEN_DEPTH, 0.3)
    chin = math.atan2(_GAZE_HEIGHT - _CAMERA_HEIGHT, distance)
    hand = math.atan2(_TALL - _CAMERA_HEIGHT, front) - half_view
    return -max(chin, hand)
