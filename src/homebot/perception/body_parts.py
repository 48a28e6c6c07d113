"""A person's head, shoulder, elbow and hand from the head camera's depth image (Cosero §7.1.3).

Cosero starts from the face, segments the person in the depth image, then the
trunk and the arms, and finds head, shoulder, elbow and hand. Here, for one RGB-D
frame and where the person stands (the leg tracker's or the camera's body
position, map frame):

1. Every depth pixel becomes a map-frame point. Pixels within ``_REACH`` of the
   person, above the floor, are the candidates; a pixel whose depth jumps from a
   neighbour's is an edge, and the candidates without edges fall into connected
   regions of the image (``cv2.connectedComponents``). The person is the regions
   that reach into their trunk's column: a table or a wall beside them is not.
2. The trunk's axis: the median of the points near it, set back by the depth a
   round trunk's seen surface lies in front of its axis, twice. The head is the
   top of the points round the axis; the shoulders lie a fixed share of a body
   below the head's top (anthropometry: about 0.19 of the stature, 0.33 m).
3. The arms: the person's points well out of the trunk's column (or above the
   trunk, beside the head), split into the person's left and right by the side
   of the line to the robot they lie on (a gesturing person faces the robot).
   The hand is the far end of the arm from the shoulder, set back by a hand's
   radius; the elbow the arm's points an upper arm's length from the shoulder.

``arm_track`` does this over a burst of frames and keeps the arm held out in
most of them; it gives the (frames, 4, 3) keypoints ``perception.gestures``
classifies. An arm that nowhere leaves the trunk hangs: its keypoints say so.
Nothing here reads the simulator: only the frames and the robot's own pose.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from homebot.geometry import Pose
from homebot.robot import CameraIntrinsics, RgbdFrame

__all__ = ["BodyParts", "arm_track", "body_parts", "looking_tilt"]

_REACH = 1.0  #: metres from the person's axis an arm can reach
_FLOOR = 0.25  #: metres: points lower are the floor's or the feet's
_JUMP = (0.05, 0.03)  #: metres, plus a share of the depth: a jump between neighbours
_CORE = 0.25  #: metres from the axis: the trunk's column
_SEEN_DEPTH = 0.13  #: metres from a trunk's seen surface back to its axis
_HEAD_COLUMN = 0.14  #: metres from the axis that the head's points lie within
_HEAD_CENTRE = 0.12  #: metres below the head's top: the eyes, the head's keypoint
_SHOULDER_DROP = 0.33  #: metres from the head's top down to the shoulders
_TRUNK_TOP = 0.2  #: metres below the head's top where the trunk ends
_OUT_OF_TRUNK = 0.28  #: metres from the axis: beyond the trunk's surface
_BESIDE_HEAD = 0.16  #: metres from the axis: beside the head, above the trunk
_ARM_DROP = 0.55  #: metres below the shoulder an arm held out can reach down to
_MIN_ARM = 12  #: pixels of an arm held out
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
    axis = _axis(points[near], centre, robot)
    if axis is None:
        return None
    regions = _regions(frame.depth, near)
    offset = points[..., :2] - axis
    distance = np.hypot(offset[..., 0], offset[..., 1])
    core = near & (distance < _CORE)
    column = core & (distance < _HEAD_COLUMN)
    if np.count_nonzero(column) < _MIN_HEAD:
        return None
    top = float(np.quantile(points[column][:, 2], 0.99))
    rows = np.nonzero(column)[0]
    if rows.min() <= _EDGE_ROWS and np.any(points[column][rows <= _EDGE_ROWS, 2] > top - 0.05):
        return None  # the head runs out of the picture: its top, and so the shoulders, unknown
    shoulder_height = top - _SHOULDER_DROP
    # the person: the image's regions that reach into the trunk's column, near its top
    upper_core = core & (points[..., 2] > shoulder_height - 0.2)
    mine = np.unique(regions[upper_core])
    person_mask = near & np.isin(regions, mine[mine > 0]) & (distance < _REACH)
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
    out = person_mask & (z > shoulder_height - _ARM_DROP) & (
        (distance > _OUT_OF_TRUNK) | ((z > top - _TRUNK_TOP) & (distance > _BESIDE_HEAD)))
    arm_points = points[out]
    across = (arm_points[:, :2] - axis) @ right
    arms = {}
    for side, sign in (("right", 1.0), ("left", -1.0)):
        chosen = arm_points[sign * across > 0]
        if len(chosen) >= _MIN_ARM:
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
    side = max(counts, key=lambda name: (counts[name], name == "right"))
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


def _regions(depth: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    """Connected regions (labels, 0: none) of the candidate pixels, cut where the depth
    jumps between neighbours."""
    filled = np.nan_to_num(depth.astype(np.float64), nan=0.0)
    limit = _JUMP[0] + _JUMP[1] * filled
    edges = np.zeros(depth.shape, dtype=bool)
    jump_x = np.abs(np.diff(filled, axis=1)) > limit[:, 1:]
    jump_y = np.abs(np.diff(filled, axis=0)) > limit[1:, :]
    edges[:, 1:] |= jump_x
    edges[:, :-1] |= jump_x
    edges[1:, :] |= jump_y
    edges[:-1, :] |= jump_y
    mask = (candidates & ~edges).astype(np.uint8)
    _, labels = cv2.connectedComponents(mask, connectivity=8)
    regions: np.ndarray = labels
    return regions


def _arm(points: np.ndarray, shoulder: np.ndarray, facing: np.ndarray
         ) -> tuple[np.ndarray, np.ndarray]:
    """Elbow and hand of an arm's points held out from ``shoulder``."""
    reach = np.linalg.norm(points - shoulder, axis=1)
    far = points[reach >= np.quantile(reach, 0.95)]
    tip = far.mean(axis=0)
    along = tip - shoulder
    along /= max(float(np.linalg.norm(along)), 1e-9)
    back = np.array([-facing[0], -facing[1], 0.0])  # the seen surface lies towards the robot
    hand = tip - _HAND_RADIUS * along + 0.5 * _HAND_RADIUS * back
    middle = np.abs(reach - _UPPER_ARM) < 0.05
    elbow = points[middle].mean(axis=0) if np.any(middle) else (shoulder + hand) / 2
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
