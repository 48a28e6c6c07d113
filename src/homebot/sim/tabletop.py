"""Generated table-top scenes with their truth: catalogue objects on a table, one camera view.

A table of random size and height stands in an empty room; the robot stands
before it as at an approach pose, its head tilted at the table; 1 to 8
catalogue objects stand on the part of the table the camera sees, turned at
random, close enough that some hide others. Used to train object recognition
and by ``homebot bench perception`` (the truth judges the pipeline there).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from homebot.robot import HeadState, RgbdFrame
from homebot.sim.camera import (
    CAMERA_HEIGHT,
    DEFAULT_INTRINSICS,
    CameraSimulator,
    SceneGeometry,
    Solid,
    camera_pose,
)
from homebot.world import CatalogueEntry

__all__ = ["PlacedObject", "TabletopScene", "tabletop_scene"]

_APPROACH_GAP = 0.37  #: metres between the robot's centre and the table's near edge
_GAP = 0.03  #: metres kept between two objects' footprints (Euclidean clustering joins closer)
_TRIES = 60


@dataclass(frozen=True, slots=True)
class PlacedObject:
    """An object in a scene: its entry and where it stands (base frame of the robot)."""

    entry: CatalogueEntry
    position: tuple[float, float, float]  #: its bottom centre, metres, base frame


@dataclass(frozen=True)
class TabletopScene:
    """One rendered view and what is truly in it."""

    frame: RgbdFrame
    objects: tuple[PlacedObject, ...]
    surface: float  #: the table's height, metres


def tabletop_scene(entries: Sequence[CatalogueEntry], count: int, rng: np.random.Generator,
                   *, noise: bool = True, gap: float = _GAP,
                   whole_in_view: bool = True) -> TabletopScene:
    """A scene with ``count`` objects drawn from ``entries`` (with replacement), ``gap``
    metres apart at least; with ``whole_in_view`` off, objects may stand partly outside
    the picture (anywhere within ±0.42 m across the line of sight)."""
    width, depth = rng.uniform(0.8, 1.6), rng.uniform(0.5, 1.0)
    surface = float(rng.uniform(0.45, 0.95))
    near = _APPROACH_GAP + float(rng.uniform(-0.05, 0.1))
    # the table's centre in the base frame; the robot faces it, off by a little
    cx, cy = near + depth / 2, float(rng.uniform(-0.1, 0.1))
    table = (cx - depth / 2, cy - width / 2, cx + depth / 2, cy + width / 2)
    drop = CAMERA_HEIGHT - surface
    tilt = math.atan2(drop, cx) + float(rng.uniform(-0.08, 0.08))
    head = HeadState(float(rng.uniform(-0.08, 0.08)), tilt)
    # objects stand where the camera sees the whole of them, on the table
    lateral = min(width / 2 - 0.08, 0.6 if whole_in_view else 0.42)
    pose = camera_pose(head)
    placed: list[tuple[CatalogueEntry, float, float, float, float]] = []
    for _ in range(count):
        entry = entries[int(rng.integers(len(entries)))]
        reach = math.hypot(entry.extent[0], entry.extent[1]) / 2
        for _ in range(_TRIES):
            x = float(rng.uniform(table[0] + reach + 0.02, table[2] - reach - 0.02))
            y = float(rng.uniform(cy - lateral, cy + lateral))
            seen = not whole_in_view or _in_view(pose, x, y, reach, surface, entry.extent[2])
            if seen and all(
                    math.dist((x, y), (ox, oy)) >= reach + other + gap
                    for _, ox, oy, _, other in placed):
                placed.append((entry, x, y, float(rng.uniform(0, math.pi)), reach))
                break
    geometry = SceneGeometry(np.zeros((0, 4)), np.array([[*table, surface]]))
    camera = CameraSimulator(geometry, rng, noise=noise)
    solids = [Solid(entry.shape, entry.extent, entry.rgb, x, y, surface, yaw)
              for entry, x, y, yaw, _ in placed]
    frame = camera.render(0.0, (0.0, 0.0, 0.0), head, solids)
    return TabletopScene(frame, tuple(PlacedObject(entry, (x, y, surface))
                                      for entry, x, y, _, _ in placed), surface)


def _in_view(pose: np.ndarray, x: float, y: float, reach: float, bottom: float,
             height: float) -> bool:
    """Whether the camera at ``pose`` sees the whole upright box round an object."""
    corners = np.array([(x + dx, y + dy, bottom + dz) for dx in (-reach, reach)
                        for dy in (-reach, reach) for dz in (0.0, height)])
    optical = (corners - pose[:3, 3]) @ pose[:3, :3]
    if np.any(optical[:, 2] < 0.1):
        return False
    k = DEFAULT_INTRINSICS
    u = k.fx * optical[:, 0] / optical[:, 2] + k.cx
    v = k.fy * optical[:, 1] / optical[:, 2] + k.cy
    return bool(np.all((u > 2) & (u < k.width - 3) & (v > 2) & (v < k.height - 3)))
