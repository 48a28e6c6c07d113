"""Qualitative relations of a whole scene at once: every pair's distance and orientation.

``scene_relations`` computes, for N things in one frame, the N × N distances and
their five distance memberships, and the N × N directions (of the second seen from
the first) with their eight orientation memberships, intrinsic (against the frame's
front) or relative (from a viewer). It is vectorised with numpy: the same functions
as ``distance`` and ``orientation``, over arrays.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from homebot.space.distance import CENTRES, DISTANCES
from homebot.space.orientation import ORIENTATIONS, SECTOR

__all__ = ["SceneRelations", "distance_membership_array", "orientation_membership_array",
           "scene_relations"]

Array = NDArray[np.float64]


def distance_membership_array(ratios: Array) -> Array:
    """``distance_memberships`` of many ``d / scale`` ratios: shape ``(*ratios.shape, 5)``."""
    ratios = np.maximum(ratios, 0.0)
    out = np.empty((*ratios.shape, len(DISTANCES)))
    centres = np.asarray(CENTRES)
    count = len(CENTRES)
    for index in range(count):
        xs = centres[max(index - 1, 0): index + 2]
        ys = np.array([1.0 if x == centres[index] else 0.0 for x in xs])
        out[..., index] = np.interp(ratios, xs, ys)
    return out


def orientation_membership_array(angles: Array) -> Array:
    """``orientation_memberships`` of many directions: shape ``(*angles.shape, 8)``."""
    position = np.mod(angles, 2 * math.pi) / SECTOR
    lower = np.floor(position)
    beyond = position - lower
    lower_index = lower.astype(np.int64) % len(ORIENTATIONS)
    upper_index = (lower_index + 1) % len(ORIENTATIONS)
    sectors = np.arange(len(ORIENTATIONS))
    degrees: Array = ((sectors == lower_index[..., None]) * (1.0 - beyond)[..., None]
                      + (sectors == upper_index[..., None]) * beyond[..., None])
    return degrees


@dataclass(frozen=True)
class SceneRelations:
    """Pairwise relations: ``distances[i, j]`` metres, ``distance_degrees[i, j, k]`` the
    membership in ``DISTANCES[k]``, ``orientation_degrees[i, j, k]`` the membership of
    j's direction seen from i in ``ORIENTATIONS[k]``."""

    names: tuple[str, ...]
    distances: Array
    distance_degrees: Array
    orientation_degrees: Array

    def index(self, name: str) -> int:
        return self.names.index(name)

    def dist(self, first: str, second: str) -> str:
        """The distance category between two things (``dist(A, B)``)."""
        degrees = self.distance_degrees[self.index(first), self.index(second)]
        return DISTANCES[int(np.argmax(degrees))]

    def orient(self, first: str, second: str) -> str:
        """The sector ``second`` lies in, seen from ``first`` (``orient(A, B)``)."""
        degrees = self.orientation_degrees[self.index(first), self.index(second)]
        return ORIENTATIONS[int(np.argmax(degrees))]


def scene_relations(points: Mapping[str, tuple[float, float]], scale: float,
                    front: float = 0.0,
                    viewer: tuple[float, float] | None = None) -> SceneRelations:
    """Every pair's relations in one frame of ``scale``. Orientations are intrinsic to the
    frame's ``front`` heading, or relative to ``viewer`` when given (the relatum's front
    faces the viewer, left is the viewer's left)."""
    if not scale > 0:
        raise ValueError(f"a frame's scale must be greater than 0, not {scale!r}")
    names = tuple(points)
    xy = np.asarray([points[name] for name in names], dtype=np.float64).reshape(-1, 2)
    delta = xy[None, :, :] - xy[:, None, :]
    distances = np.hypot(delta[..., 0], delta[..., 1])
    directions = np.arctan2(delta[..., 1], delta[..., 0])
    if viewer is None:
        angles = directions - front
    else:
        sight = np.arctan2(xy[:, 1] - viewer[1], xy[:, 0] - viewer[0])
        angles = math.pi - (directions - sight[:, None])
    return SceneRelations(names, distances, distance_membership_array(distances / scale),
                          orientation_membership_array(angles))
