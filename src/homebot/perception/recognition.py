"""Object recognition on table-top segments: a random forest trained from the catalogue.

Each segment's features (``homebot.perception.tabletop.cluster_features``) go to a
scikit-learn ``RandomForestClassifier`` whose classes are the catalogue's objects;
the category is the recognised object's. The forest learns from labelled
examples: views of catalogue objects, rendered and segmented by the same
pipeline (``training_examples`` takes any source of frames with their truth, so
the simulator renders them and this layer never imports it).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from homebot.perception.tabletop import cluster_features, segment_tabletop
from homebot.robot import RgbdFrame
from homebot.world import CatalogueEntry

__all__ = [
    "LabelledFrame",
    "ObjectEstimate",
    "Recogniser",
    "TabletopPerception",
    "fits",
    "match_positions",
    "training_examples",
]

#: a frame and the objects truly in it: (object name, bottom centre in the base frame)
LabelledFrame = tuple[RgbdFrame, Sequence[tuple[str, tuple[float, float, float]]]]
_MATCH = 0.05  #: metres within which a segment is the object it is matched to
_OVERSIZE = 1.5  #: a cluster this many times bigger than what it looks most like is not it
_SIZE_SLACK = 0.05  #: metres on top of that: noise, a stray edge pixel


@dataclass(frozen=True, slots=True)
class ObjectEstimate:
    """An object as perception estimates it (base frame of the camera's robot)."""

    label: str  #: the catalogue object it looks most like
    category: str
    confidence: float  #: the forest's vote share for ``label``
    position: tuple[float, float, float]  #: bottom centre, metres
    size: float  #: largest measured dimension, metres
    height: float  #: metres above the support plane
    rgb: tuple[int, int, int]  #: median colour seen
    mass: float  #: kg, the recognised object's
    truncated: bool = False  #: it reaches the picture's edge: part of it may be outside
    #: radians, base frame: the heading of the recognised box's x side, from a minimum-area
    #: rectangle fitted to the top face (None: not a box, or too few points)
    heading: float | None = None


def box_heading(top: np.ndarray, extent: Sequence[float]) -> float | None:
    """The heading (radians, in the points' frame, modulo pi) of a box's x side, from the
    minimum-area rectangle round its top face's points (``cv2.minAreaRect``): of the
    rectangle's two sides, the one whose length is nearer the box's x extent is its x side.
    None for fewer than five points."""
    if len(top) < 5:
        return None
    import cv2

    (_, _), (first, second), degrees = cv2.minAreaRect(np.asarray(top[:, :2], np.float32))
    angle = math.radians(degrees)
    x_side, y_side = float(extent[0]), float(extent[1])
    first_is_x = abs(first - x_side) + abs(second - y_side) <= \
        abs(first - y_side) + abs(second - x_side)
    heading = angle if first_is_x else angle + math.pi / 2
    return math.atan2(math.sin(2 * heading), math.cos(2 * heading)) / 2


def fits(entry: CatalogueEntry, height: float, major: float) -> bool:
    """Whether a cluster ``height`` tall whose footprint spreads ``major`` along its longer
    axis (metres) could be ``entry`` standing upright: neither more than ``_OVERSIZE`` times
    the object's height or footprint's diagonal, and ``_SIZE_SLACK`` more."""
    x, y, z = entry.extent
    return (height <= _OVERSIZE * z + _SIZE_SLACK
            and major <= _OVERSIZE * math.hypot(x, y) + _SIZE_SLACK)


def match_positions(estimated: Sequence[Sequence[float]], truth: Sequence[Sequence[float]],
                    radius: float = _MATCH) -> list[tuple[int, int]]:
    """One-to-one pairs (estimate index, truth index) closer than ``radius`` in the plane,
    by least total distance (Hungarian assignment)."""
    if not len(estimated) or not len(truth):
        return []
    a = np.asarray(estimated, dtype=np.float64)[:, :2]
    b = np.asarray(truth, dtype=np.float64)[:, :2]
    cost = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    rows, cols = linear_sum_assignment(np.where(cost <= radius, cost, 1e6))
    return [(int(r), int(c)) for r, c in zip(rows, cols, strict=True) if cost[r, c] <= radius]


def training_examples(frames: Iterable[LabelledFrame],
                      rng: np.random.Generator) -> tuple[np.ndarray, list[str]]:
    """Features and object names of every segment that matches a true object."""
    features: list[np.ndarray] = []
    labels: list[str] = []
    for frame, truth in frames:
        segments = segment_tabletop(frame, rng).segments
        pairs = match_positions([s.position() for s in segments], [t[1] for t in truth])
        for segment_index, truth_index in pairs:
            features.append(cluster_features(segments[segment_index]))
            labels.append(truth[truth_index][0])
    return (np.array(features) if features else np.zeros((0, 0))), labels


class Recogniser:
    """Which catalogue object a segment is: a random forest over segment features.

    Args:
        catalogue: the objects it can name, by name.
        seed: the forest's randomness.
        trees: how many trees.
    """

    def __init__(self, catalogue: Mapping[str, CatalogueEntry], *, seed: int = 0,
                 trees: int = 30) -> None:
        from sklearn.ensemble import RandomForestClassifier

        self.catalogue = dict(catalogue)
        self.forest = RandomForestClassifier(n_estimators=trees, random_state=seed,
                                             min_samples_leaf=1, n_jobs=1)
        self.trained = False

    def fit(self, features: np.ndarray, labels: Sequence[str]) -> Recogniser:
        """Learn from labelled segment features; returns itself."""
        unknown = sorted(set(labels) - set(self.catalogue))
        if unknown:
            raise ValueError(f"labels not in the catalogue: {', '.join(unknown)}")
        self.forest.fit(features, list(labels))
        self.trained = True
        return self

    def predict(self, features: np.ndarray) -> list[tuple[str, float]]:
        """The most likely object and its vote share, per row of ``features`` (``""`` and 0
        while untrained: a catalogue with no objects)."""
        if not len(features):
            return []
        if not self.trained:
            return [("", 0.0)] * len(features)
        votes = self.forest.predict_proba(features)
        best = votes.argmax(axis=1)
        classes = self.forest.classes_
        return [(str(classes[i]), float(votes[row, i])) for row, i in enumerate(best)]


def _at_edge(frame: RgbdFrame, points: np.ndarray, margin: int = 3) -> bool:
    """Whether any of ``points`` (base frame) shows within ``margin`` pixels of the edge."""
    rotation, translation = frame.camera_pose[:3, :3], frame.camera_pose[:3, 3]
    optical = (points - translation) @ rotation
    k = frame.intrinsics
    depth = np.maximum(optical[:, 2], 1e-6)
    u = k.fx * optical[:, 0] / depth + k.cx
    v = k.fy * optical[:, 1] / depth + k.cy
    return bool(np.any((u < margin) | (u > k.width - 1 - margin) | (v < margin)
                       | (v > k.height - 1 - margin)))


class TabletopPerception:
    """The whole pipeline for one frame: segment, describe, recognise, estimate.

    Args:
        recogniser: a trained recogniser.
        rng: RANSAC's draws.
    """

    def __init__(self, recogniser: Recogniser, rng: np.random.Generator) -> None:
        self.recogniser = recogniser
        self.rng = rng

    def perceive(self, frame: RgbdFrame,
                 expected_height: float | None = None) -> list[ObjectEstimate]:
        """The objects on the support surface in ``frame`` (base frame positions)."""
        segments = segment_tabletop(frame, self.rng, expected_height=expected_height).segments
        if not segments:
            return []
        features = np.array([cluster_features(segment) for segment in segments])
        estimates = []
        for segment, row, (label, confidence) in zip(
                segments, features, self.recogniser.predict(features), strict=True):
            entry = self.recogniser.catalogue.get(label)
            height, major = float(row[0]), float(row[1])
            if entry is not None and not fits(entry, height, major):
                continue  # nothing it knows is that big: a person lying there, a blanket
            rgb = np.median(segment.colours, axis=0)
            estimates.append(ObjectEstimate(
                label or "object", entry.category if entry else "object", confidence,
                segment.position(), max(height, major), height,
                (int(rgb[0]), int(rgb[1]), int(rgb[2])), entry.mass if entry else 0.0,
                _at_edge(frame, segment.points),
                box_heading(segment.top(), entry.extent[:2])
                if entry is not None and entry.shape.value == "box" else None))
        return estimates
