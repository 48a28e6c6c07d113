"""A plant pot's rim from the torso laser: where its centre is and how high its rim.

Cosero positions itself relative to the plant pot it perceives in its laser scanner
(§6.4.3). ``PotScan`` sweeps the pitchable torso laser: horizontal fans of rays at
elevations from a little below the horizontal to well above the rim's height. Of the
points it returns, the pot is the nearest upright thing in front of the robot (a run of
neighbouring rays at a similar range in the horizontal fan); its rim is the highest
point of it the rays still meet (a ray just above the rim passes over the pot); its
wall is what lies a few centimetres below the rim, and a circle fitted to the wall's
points by least squares (``cv2``-free: an algebraic fit refined on the points'
distances by ``scipy.optimize.least_squares``) gives the rim's centre. Everything here
comes from the laser's ranges and the torso's height; nothing reads the scene.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PotScan", "SeenPot", "fit_circle"]

#: The torso laser's position (base frame) with the torso lift at zero.
MOUNT = np.array([0.1, 0.0, 0.45])


@dataclass(frozen=True)
class SeenPot:
    """The pot as the laser shows it (base frame)."""

    rim: np.ndarray  #: the rim's centre: x, y and the rim's height
    radius: float  #: the fitted wall's radius (m)
    points: int  #: wall points the circle was fitted to


def fit_circle(points: np.ndarray) -> tuple[np.ndarray, float]:
    """The circle (centre, radius) through 2-D ``points`` in the least-squares sense."""
    from scipy.optimize import least_squares

    xy = np.asarray(points, dtype=float)
    # Algebraic (Kasa) fit: x² + y² + D x + E y + F = 0, linear in D, E, F.
    a = np.column_stack((xy[:, 0], xy[:, 1], np.ones(len(xy))))
    b = -(xy[:, 0] ** 2 + xy[:, 1] ** 2)
    (d, e, f), *_ = np.linalg.lstsq(a, b, rcond=None)
    centre = np.array([-d / 2, -e / 2])
    radius = float(np.sqrt(max(1e-6, centre @ centre - f)))

    def off(p: np.ndarray) -> np.ndarray:
        distances: np.ndarray = np.linalg.norm(xy - p[:2], axis=1) - p[2]
        return distances

    fitted = least_squares(off, np.array([*centre, radius]), loss="soft_l1", f_scale=0.01)
    return np.asarray(fitted.x[:2], dtype=float), float(fitted.x[2])


class PotScan:
    """Find a pot in front of the robot with a sweep of the torso laser.

    Args:
        across: the fans' half-width and step (degrees).
        elevations: first, last and step of the fans' elevations (degrees, up positive).
        wall: how far below the rim (m) the points the circle is fitted to lie.
        reach: metres from the robot's base within which the pot is looked for.
    """

    def __init__(self, *, across: tuple[float, float] = (45.0, 0.5),
                 elevations: tuple[float, float, float] = (-5.0, 25.0, 0.5),
                 wall: tuple[float, float] = (0.01, 0.07), reach: float = 2.0) -> None:
        half, step = across
        azimuths = np.radians(np.arange(-half, half + step / 2, step))
        first, last, rise = elevations
        lifts = np.radians(np.arange(first, last + rise / 2, rise))
        azimuth, elevation = np.meshgrid(azimuths, lifts)
        self.azimuth, self.elevation = azimuth.ravel(), elevation.ravel()
        self.wall, self.reach = wall, reach

    def mount(self, torso: float) -> np.ndarray:
        """The laser's position (base frame) at the torso lift's height ``torso``."""
        mount: np.ndarray = MOUNT + np.array([0.0, 0.0, torso])
        return mount

    def directions(self) -> np.ndarray:
        """The sweep's unit rays (base frame), one a row."""
        c = np.cos(self.elevation)
        return np.column_stack((c * np.cos(self.azimuth), c * np.sin(self.azimuth),
                                np.sin(self.elevation)))

    def find(self, torso: float, ranges: np.ndarray) -> SeenPot | None:
        """The pot in one sweep (``ranges`` along ``directions()`` from ``mount(torso)``);
        None if nothing in reach looks like one."""
        ranges = np.asarray(ranges, dtype=float)
        seen = np.isfinite(ranges)
        points = self.mount(torso) + self.directions()[seen] * ranges[seen, None]
        level = np.linalg.norm(points[:, :2], axis=1)
        upright = (points[:, 2] > 0.05) & (level < self.reach)  # not the floor
        points = points[upright]
        if len(points) < 10:
            return None
        # The nearest upright thing: the points within 0.3 m (across) of the nearest one.
        nearest = points[int(np.argmin(np.linalg.norm(points[:, :2], axis=1)))]
        near = points[np.linalg.norm(points[:, :2] - nearest[:2], axis=1) < 0.3]
        rim = float(np.max(near[:, 2]))
        low, high = self.wall
        wall = near[(near[:, 2] < rim - low) & (near[:, 2] > rim - high)]
        if len(wall) < 8:
            return None
        centre, radius = fit_circle(wall[:, :2])
        return SeenPot(np.array([centre[0], centre[1], rim]), radius, len(wall))
