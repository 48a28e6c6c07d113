"""Table-top segmentation (Cosero §6.1.1): support plane by RANSAC, objects by clustering.

The depth image is back-projected to a point cloud in the robot's base frame. A
RANSAC fit finds the largest plane whose normal is within a few degrees of
vertical (the table, never a wall; the floor is left out by height). The points
above that plane and inside its outline are grouped by Euclidean distance; each
group is one object candidate with its features (extent, colour, shape cues)
and a position: the centre of its top face, which the camera looks down on.

Small pure functions in Open3D's style (numpy in, numpy out, no hidden state):
``plane_hypothesis``, ``segment_plane``, ``cluster``, ``split_by_colour``, ``segment_tabletop``,
``cluster_features``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.cluster.vq import kmeans2
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import ConvexHull, QhullError, cKDTree

from homebot.robot import RgbdFrame

__all__ = [
    "FEATURE_NAMES",
    "Plane",
    "Segment",
    "Tabletop",
    "cluster",
    "cluster_features",
    "plane_hypothesis",
    "row_spacing",
    "segment_plane",
    "segment_tabletop",
    "split_by_colour",
]

_FLOOR_CLEARANCE = 0.2  #: metres: a support plane lies higher than this (not the floor)
_PLANE_DISTANCE = 0.012  #: metres from the plane that still count as on it
_MAX_TILT = 0.1  #: radians between a support plane's normal and the vertical
_ABOVE = (0.012, 0.6)  #: metres above the plane where object points are
_EDGE_MARGIN = 0.01  #: metres inside the plane's outline an object point must lie
_CLUSTER_DISTANCE = 0.016  #: metres between neighbouring points of one object
_CENTRE_BAND = 0.004  #: metres below the top whose points centre an object (see ``position``)
_SPHERE_MISFIT = 0.004  #: metres (rms) within which points lie on a sphere
_SPHERE_REST = 0.3  #: a resting sphere's centre is its radius above the plane, within this share
_SPHERE_LARGEST = 0.2  #: metres: no ball on a table is bigger
_MIN_POINTS = 12  #: smaller groups are noise
#: radians between the two colours (as RGB vectors, whose direction light does not change)
#: a group must show, each in a part of its own, before it is split into two objects ...
_HUE_SPLIT = 0.1
_SPLIT_CONTRAST = 3.0  #: ... and this many times the spread of colours within each part
_SPLIT_SHARE = 0.08  #: each part holds at least this share of the group's points
_DARK = 60.0  #: colours shorter than this (of 441) are too noisy to tell hues apart
_SPLITS = 3  #: a group is split at most this many times over (four objects in one)
_KMEANS_SEED = 0  #: the k-means's own draws, apart from RANSAC's
_VOXEL = 0.006  #: metres: object points are thinned to one per voxel before clustering
_ROWS_JOINED = 1.4  #: a point joins neighbours this many row spacings away ...
_MAX_REACH = 0.04  #: ... but never farther than this (metres)
_PLANE_SHARE = 4  #: RANSAC looks for the plane among every 4th point
_SAMPLE = 4000  #: points RANSAC scores each hypothesis on

#: what ``cluster_features`` returns, in order
FEATURE_NAMES = ("height", "major", "minor", "top_share", "top_fill", "top_width_ratio",
                 "red", "green", "blue", "brightness", "saturation")


@dataclass(frozen=True, slots=True)
class Plane:
    """``z = a x + b y + c`` in the base frame, and the outline of its points."""

    a: float
    b: float
    c: float
    inliers: int
    #: (k, 3) half-planes of its outline: inside where ``hull[:, :2] @ xy + hull[:, 2] <= 0``
    hull: np.ndarray

    def height_of(self, points: np.ndarray) -> np.ndarray:
        """Each point's height above the plane."""
        above: np.ndarray = points[:, 2] - (self.a * points[:, 0] + self.b * points[:, 1]
                                            + self.c)
        return above


@dataclass(frozen=True, slots=True)
class Segment:
    """One object candidate: its points (base frame), their colours and heights."""

    points: np.ndarray
    colours: np.ndarray
    heights: np.ndarray  #: above the support plane

    def top(self, band: float = 0.01) -> np.ndarray:
        """The points of its top face (within ``band`` metres of its highest)."""
        peak = float(np.percentile(self.heights, 98))
        band = min(band, 0.2 * peak)
        top: np.ndarray = self.points[self.heights >= peak - band]
        return top

    def position(self) -> tuple[float, float, float]:
        """Where it stands (base frame): under the centre of its top face, on the plane.

        The centre is the middle of the top's spread along the line of sight and
        across it (2nd to 98th percentile), not the mean of its points: seen at a
        grazing angle, the near rim of a top face has more points than the far one.
        The top here is only the points within a few millimetres of the highest. A ball
        (a fruit) has no top face, and the camera sees its near side only: when the
        points lie on a sphere resting on the plane, its centre is the fitted sphere's.
        """
        bottom = self.points[:, 2] - self.heights
        ball = _resting_sphere(self.points, float(np.mean(bottom)))
        if ball is not None:
            return (ball[0], ball[1], float(np.mean(bottom)))
        top = self.top(_CENTRE_BAND)[:, :2]
        middle = top.mean(axis=0)
        sight = middle / (float(np.linalg.norm(middle)) or 1.0)
        frame = np.array([sight, (-sight[1], sight[0])])  # along, across the line of sight
        along = top @ frame.T
        low, high = np.percentile(along, [2, 98], axis=0)
        centre = ((low + high) / 2) @ frame
        return (float(centre[0]), float(centre[1]), float(np.mean(bottom)))


@dataclass(frozen=True, slots=True)
class Tabletop:
    """A segmented frame: the support plane (None: none found) and the objects on it."""

    plane: Plane | None
    segments: tuple[Segment, ...]


def _resting_sphere(points: np.ndarray, plane: float) -> tuple[float, float] | None:
    """The centre (x, y) of the sphere the points lie on, if they do and it rests at height
    ``plane``; None otherwise. An algebraic least-squares fit (linear in the centre)."""
    if len(points) < 4 * _MIN_POINTS:
        return None
    system = np.column_stack((2 * points, np.ones(len(points))))
    solution, *_ = np.linalg.lstsq(system, np.einsum("ij,ij->i", points, points), rcond=None)
    centre = solution[:3]
    squared = float(solution[3] + centre @ centre)
    if squared <= 0:
        return None
    radius = math.sqrt(squared)
    misfit = float(np.sqrt(np.mean((np.linalg.norm(points - centre, axis=1) - radius) ** 2)))
    resting = abs(centre[2] - plane - radius) <= _SPHERE_REST * radius
    if misfit > _SPHERE_MISFIT or not resting or radius > _SPHERE_LARGEST:
        return None
    return (float(centre[0]), float(centre[1]))


def plane_hypothesis(points: np.ndarray, distance: float, iterations: int,
                     rng: np.random.Generator, *, vertical_normal: bool,
                     max_tilt: float) -> tuple[np.ndarray, float] | None:
    """RANSAC's best guess: of ``iterations`` planes through three of ``points`` (at least
    three) drawn at random, whose normal lies within ``max_tilt`` of the vertical
    (``vertical_normal``: a floor, a table) or of the horizontal (a wall, a door's leaf),
    the one most points lie within ``distance`` of (scored on at most ``_SAMPLE`` of
    them): ``(normal, offset)`` of ``normal·p + offset = 0``; None when no draw gives
    such a plane."""
    count = len(points)
    scored = points if count <= _SAMPLE else points[rng.choice(count, _SAMPLE, replace=False)]
    picks = points[rng.integers(0, count, (iterations, 3))]
    normals = np.cross(picks[:, 1] - picks[:, 0], picks[:, 2] - picks[:, 0])
    length = np.linalg.norm(normals, axis=1)
    vertical = np.abs(normals[:, 2])
    kept = (length > 1e-9) & (vertical >= np.cos(max_tilt) * length if vertical_normal
                              else vertical <= np.sin(max_tilt) * length)
    if not np.any(kept):
        return None
    normals, picks = normals[kept] / length[kept, None], picks[kept]
    offsets = -np.einsum("ij,ij->i", normals, picks[:, 0])
    residuals = np.abs(scored @ normals.T + offsets)  # (points, hypotheses)
    best = int(np.argmax((residuals < distance).sum(axis=0)))
    return normals[best], float(offsets[best])


def segment_plane(points: np.ndarray, distance: float, iterations: int,
                  rng: np.random.Generator,
                  max_tilt: float = _MAX_TILT) -> tuple[np.ndarray, np.ndarray]:
    """RANSAC for the plane with the most points whose normal is near vertical.

    Returns ``(model, inlier_indices)``: ``model`` is ``(a, b, c)`` of ``z = a x + b y + c``
    (least squares over the inliers); empty inliers when no plane was found.
    """
    if len(points) < 3:
        return np.zeros(3), np.zeros(0, dtype=np.int64)
    found = plane_hypothesis(points, distance, iterations, rng, vertical_normal=True,
                             max_tilt=max_tilt)
    if found is None:
        return np.zeros(3), np.zeros(0, dtype=np.int64)
    normal, offset = found
    inliers = np.flatnonzero(np.abs(points @ normal + offset) < distance)
    model = _fit(points[inliers])
    residual = np.abs(points[:, 2] - (model[0] * points[:, 0] + model[1] * points[:, 1]
                                      + model[2]))
    return model, np.flatnonzero(residual < distance)


def _fit(points: np.ndarray) -> np.ndarray:
    """Least squares ``z = a x + b y + c``."""
    design = np.column_stack((points[:, 0], points[:, 1], np.ones(len(points))))
    model: np.ndarray = np.linalg.lstsq(design, points[:, 2], rcond=None)[0]
    return model


def cluster(points: np.ndarray, eps: float, min_points: int,
            reach: np.ndarray | None = None) -> np.ndarray:
    """Euclidean clustering: points closer than ``eps`` are one group; labels, -1 for groups
    smaller than ``min_points``. ``reach`` (per point, at least ``eps``) lets a point join
    farther neighbours: where the camera's rows lie far apart on a surface seen edge-on."""
    count = len(points)
    if count == 0:
        return np.zeros(0, dtype=np.int64)
    tree = cKDTree(points)
    pairs = tree.query_pairs(eps, output_type="ndarray")
    if reach is not None:
        far = np.flatnonzero(reach > eps)
        if len(far):
            found = tree.query_ball_point(points[far], reach[far])
            sizes = np.fromiter((len(near) for near in found), dtype=np.int64, count=len(far))
            if sizes.sum():
                first = np.repeat(far, sizes)
                second = np.concatenate([near for near in found if near]).astype(np.int64)
                joined = reach[second] > eps
                pairs = np.vstack((pairs.reshape(-1, 2),
                                   np.column_stack((first[joined], second[joined]))))
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(count, count))
    _, labels = connected_components(graph, directed=False)
    sizes = np.bincount(labels)
    small = sizes[labels] < min_points
    kept = np.unique(labels[~small])
    renumber = np.full(len(sizes), -1)
    renumber[kept] = np.arange(len(kept))
    result: np.ndarray = np.where(small, -1, renumber[labels])
    return result


def row_spacing(points: np.ndarray, camera: np.ndarray, focal: float) -> np.ndarray:
    """How far apart neighbouring image rows fall on a horizontal surface at each point:
    ``r² / (f Δh)`` for a point ``r`` from the camera and ``Δh`` below it."""
    ranges = np.linalg.norm(points - camera, axis=1)
    below = np.maximum(camera[2] - points[:, 2], 0.01)
    spacing: np.ndarray = ranges * ranges / (focal * below)
    return spacing


def segment_tabletop(frame: RgbdFrame, rng: np.random.Generator, *,
                     expected_height: float | None = None,
                     iterations: int = 60) -> Tabletop:
    """The support plane in ``frame`` and the object candidates standing on it.

    Args:
        frame: the camera image.
        rng: RANSAC's draws.
        expected_height: where the surface should be (metres above the floor), if known:
            the plane is then looked for within 15 cm of it.
        iterations: RANSAC hypotheses.
    """
    points, colours = frame.points()
    sample = points[::_PLANE_SHARE]
    high = sample[:, 2] > _FLOOR_CLEARANCE
    if expected_height is not None:
        high &= np.abs(sample[:, 2] - expected_height) < 0.15
    candidates = sample[high]
    model, inliers = segment_plane(candidates, _PLANE_DISTANCE, iterations, rng)
    if len(inliers) < 200:
        return Tabletop(None, ())
    outline = candidates[inliers][:, :2]
    try:
        hull = ConvexHull(outline)
    except QhullError:
        return Tabletop(None, ())
    plane = Plane(float(model[0]), float(model[1]), float(model[2]), len(inliers),
                  hull.equations)
    heights = plane.height_of(points)
    chosen = np.flatnonzero((heights > _ABOVE[0]) & (heights < _ABOVE[1]))
    inside = np.all(points[chosen, :2] @ plane.hull[:, :2].T + plane.hull[:, 2]
                    <= -_EDGE_MARGIN, axis=1)
    chosen = chosen[inside]
    chosen = chosen[_voxel_thin(points[chosen], _VOXEL)]
    spacing = row_spacing(points[chosen], frame.camera_pose[:3, 3], frame.intrinsics.fy)
    reach = np.clip(_ROWS_JOINED * spacing, _CLUSTER_DISTANCE, _MAX_REACH)
    labels = cluster(points[chosen], _CLUSTER_DISTANCE, _MIN_POINTS, reach)
    segments = []
    for label in range(int(labels.max(initial=-1)) + 1):
        in_group = labels == label
        for part in split_by_colour(points[chosen][in_group], colours[chosen][in_group],
                                    reach[in_group]):
            members = chosen[in_group][part]
            segments.append(Segment(points[members], colours[members], heights[members]))
    return Tabletop(plane, tuple(segments))


def split_by_colour(points: np.ndarray, colours: np.ndarray, reach: np.ndarray,
                    depth: int = _SPLITS) -> list[np.ndarray]:
    """The objects in one Euclidean group, as index arrays into it: two objects that touch
    (a banana leaning on a cup) are one group, but each has its own colour.

    The colours' directions (light changes a colour's length, not its direction) are
    split in two by k-means; the group is split when the two hues lie ``_HUE_SPLIT`` apart
    and ``_SPLIT_CONTRAST`` times the spread within each (a single colour's noise, split in
    two, is never that far apart), and each part holds ``_SPLIT_SHARE`` of the points. Each
    part is clustered again by distance (a stray pixel of the other hue drops out) and
    split again, down to ``depth`` times."""
    whole = [np.arange(len(points))]
    if depth <= 0 or len(points) < 2 * _MIN_POINTS:
        return whole
    values = colours.astype(np.float64)
    length = np.linalg.norm(values, axis=1)
    bright = length >= _DARK
    if np.count_nonzero(bright) < 2 * _MIN_POINTS:
        return whole
    hues = values[bright] / length[bright, None]
    # two hues _HUE_SPLIT apart, the lesser holding _SPLIT_SHARE, spread the whole this far
    # about its mean at least: most groups, of one colour, stop here, before the k-means
    least = _HUE_SPLIT * math.sqrt(_SPLIT_SHARE * (1 - _SPLIT_SHARE))
    if float(np.sqrt(np.mean(np.sum((hues - hues.mean(axis=0)) ** 2, axis=1)))) < least:
        return whole
    # its own fixed draws: a split leaves the caller's RANSAC draws as they were
    centres, assigned = kmeans2(hues, 2, minit="++", seed=_KMEANS_SEED)
    counts = np.bincount(assigned, minlength=2)
    if counts.min() < max(_MIN_POINTS, _SPLIT_SHARE * len(hues)):
        return whole
    unit = centres / np.linalg.norm(centres, axis=1, keepdims=True)
    apart = float(np.arccos(np.clip(unit[0] @ unit[1], -1.0, 1.0)))
    spread = float(np.sqrt(np.mean(np.sum((hues - centres[assigned]) ** 2, axis=1))))
    if apart < _HUE_SPLIT or apart < _SPLIT_CONTRAST * spread:
        return whole
    # every point, the dark ones too, goes with the nearer hue
    nearer = np.argmax(values @ unit.T, axis=1)
    parts: list[np.ndarray] = []
    for side in (0, 1):
        members = np.flatnonzero(nearer == side)
        labels = cluster(points[members], _CLUSTER_DISTANCE, _MIN_POINTS, reach[members])
        for label in range(int(labels.max(initial=-1)) + 1):
            piece = members[labels == label]
            parts.extend(piece[sub] for sub in split_by_colour(
                points[piece], colours[piece], reach[piece], depth - 1))
    return parts or whole


def _voxel_thin(points: np.ndarray, size: float) -> np.ndarray:
    """Indices of one point per ``size`` voxel (the first in image order), sorted."""
    if len(points) == 0:
        return np.zeros(0, dtype=np.int64)
    cells = np.floor(points / size).astype(np.int64)
    cells -= cells.min(axis=0)
    span = cells.max(axis=0) + 1
    keys = (cells[:, 0] * span[1] + cells[:, 1]) * span[2] + cells[:, 2]
    _, first = np.unique(keys, return_index=True)
    return np.sort(first)


def cluster_features(segment: Segment) -> np.ndarray:
    """The features ``FEATURE_NAMES`` name: size, shape cues and colour of one candidate."""
    heights = segment.heights
    height = float(np.percentile(heights, 98))
    xy = segment.points[:, :2]
    major, minor = _extents(xy)
    top = segment.top()
    top_share = len(top) / len(xy)
    top_major, top_minor = _extents(top[:, :2]) if len(top) >= 3 else (0.0, 0.0)
    top_fill = _fill(top[:, :2], top_major, top_minor)
    middle = segment.points[np.abs(heights - height / 2) < max(0.1 * height, 0.005)]
    middle_width = _extents(middle[:, :2])[1] if len(middle) >= 3 else minor
    ratio = top_minor / middle_width if middle_width > 1e-6 else 1.0
    rgb = np.median(segment.colours.astype(np.float64), axis=0)
    total = float(rgb.sum()) or 1.0
    brightest, darkest = float(rgb.max()), float(rgb.min())
    saturation = (brightest - darkest) / brightest if brightest > 0 else 0.0
    return np.array([height, major, minor, top_share, top_fill, ratio,
                     rgb[0] / total, rgb[1] / total, rgb[2] / total, brightest / 255.0,
                     saturation])


def _extents(xy: np.ndarray) -> tuple[float, float]:
    """The spread (2nd to 98th percentile) of points along their two principal axes."""
    if len(xy) < 3:
        return (0.0, 0.0)
    centred = xy - xy.mean(axis=0)
    _, vectors = np.linalg.eigh(np.cov(centred.T))
    along = centred @ vectors
    low, high = np.percentile(along, [2, 98], axis=0)
    spread = high - low
    return (float(spread[1]), float(spread[0]))


def _fill(xy: np.ndarray, major: float, minor: float) -> float:
    """How much of its bounding rectangle the top face's outline fills (box 1, disc π/4)."""
    if len(xy) < 4 or major * minor <= 0:
        return 0.0
    try:
        area = float(ConvexHull(xy).volume)
    except QhullError:
        return 0.0
    return min(area / (major * minor), 1.5)
