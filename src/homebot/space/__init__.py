"""Qualitative space: fuzzy distances, orientations, frames of reference, referring expressions.

CAESAR's qualitative world model (§3.4): five overlapping distance categories scaled
by a frame, eight orientation sectors read intrinsically or from a viewer, frames
nested world → room → furniture → object, and the resolution of "the left cup close
to the plate" among the things the robot sees. A knowledge-layer package: it reads
the world model, nothing above it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.lazy import lazy_exports

if TYPE_CHECKING:
    from homebot.space.distance import (
        BOUNDARIES,
        CENTRES,
        DISTANCES,
        at_most,
        closeness,
        distance_category,
        distance_memberships,
        is_distance,
    )
    from homebot.space.frames import Frame, Frames, frames_of
    from homebot.space.orientation import (
        ORIENTATIONS,
        intrinsic_angle,
        orientation_category,
        orientation_memberships,
        relative_angle,
        side_degree,
    )
    from homebot.space.places import resolve_place
    from homebot.space.referring import MARGIN, Modifier, Resolution, Scene, resolve, split_spatial
    from homebot.space.relations import SceneRelations, scene_relations

__all__ = [
    "BOUNDARIES",
    "CENTRES",
    "DISTANCES",
    "MARGIN",
    "ORIENTATIONS",
    "Frame",
    "Frames",
    "Modifier",
    "Resolution",
    "Scene",
    "SceneRelations",
    "at_most",
    "closeness",
    "distance_category",
    "distance_memberships",
    "frames_of",
    "intrinsic_angle",
    "is_distance",
    "orientation_category",
    "orientation_memberships",
    "relative_angle",
    "resolve",
    "resolve_place",
    "scene_relations",
    "side_degree",
    "split_spatial",
]

__getattr__ = lazy_exports(globals())
