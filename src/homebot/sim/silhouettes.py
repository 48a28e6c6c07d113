"""What a head camera shows of a person: a point cloud of their body and a patch of their top.

``person_cloud`` samples a standing, sitting or lying body (a stack of ellipses
for legs, trunk and head; a seated body folds at the hip, a lying one stretches
along the floor or a bed) as depth points with noise, some lost to occlusion.
``torso_patch`` renders the top's colour under a seeded light level, a colour
cast and sensor noise. Both judge ``homebot.perception.people``'s posture and
clothes-colour estimates against the person's true posture and colour.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["POSTURES", "person_cloud", "torso_patch"]

POSTURES = ("standing", "sitting", "lying")


def person_cloud(position: tuple[float, float], posture: str, rng: np.random.Generator,
                 *, height: float | None = None, points: int = 400,
                 noise: float = 0.015) -> np.ndarray:
    """Points (n, 3) on the map of a person of ``height`` (drawn 1.55–1.95 m when None)."""
    if posture not in POSTURES:
        raise ValueError(f"unknown posture {posture!r}; one of {', '.join(POSTURES)}")
    tall = height if height is not None else float(rng.uniform(1.55, 1.95))
    heading = float(rng.uniform(0.0, 2 * math.pi))
    along = np.array([math.cos(heading), math.sin(heading)])
    u = rng.uniform(0.0, 1.0, points)  # where along the body, feet (0) to head (1)
    across = rng.normal(0.0, 0.12, points)
    if posture == "standing":
        offset, z = np.zeros(points), u * tall
    elif posture == "sitting":
        seat = 0.45
        thigh = u < 0.28  # feet to knees hang down, knees to hip run level on the seat
        z = np.where(thigh, np.minimum(u / 0.14, 1.0) * seat, seat + (u - 0.28) / 0.72 *
                     (tall * 0.53))
        offset = np.where(thigh, np.maximum(u - 0.14, 0.0) / 0.14 * 0.45, 0.45)
    else:
        bed = float(rng.choice([0.05, 0.5]))  # on the floor or on a bed
        offset, z = u * tall, bed + rng.uniform(0.0, 0.25, points)
    x = position[0] + offset * along[0] - across * along[1]
    y = position[1] + offset * along[1] + across * along[0]
    cloud = np.column_stack((x, y, z)) + rng.normal(0.0, noise, (points, 3))
    kept = rng.random(points) > rng.uniform(0.0, 0.4)  # occlusion drops a share
    sample: np.ndarray = cloud[kept]
    return sample


def torso_patch(rgb: tuple[int, int, int], rng: np.random.Generator, *, size: int = 16,
                light: float = 0.35, cast: float = 0.06, noise: float = 10.0) -> np.ndarray:
    """A (size, size, 3) uint8 patch of a top of colour ``rgb``, lit ±``light``, with a
    colour cast of ±``cast`` per channel and Gaussian ``noise`` (grey levels)."""
    gain = 1.0 + rng.uniform(-light, light)
    tint = 1.0 + rng.uniform(-cast, cast, 3)
    shading = 1.0 + 0.15 * np.linspace(-1.0, 1.0, size)[None, :, None]  # folds, side light
    patch = np.asarray(rgb, dtype=float)[None, None, :] * gain * tint * shading
    patch = patch + rng.normal(0.0, noise, (size, size, 3))
    image: np.ndarray = np.clip(patch, 0, 255).astype(np.uint8)
    return image
