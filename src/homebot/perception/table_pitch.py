"""The pitch of a table the robot carries with a person, from a laser fan over its top.

Cosero keeps track of the table it carries by registering it in its RGB-D images (§7.3.3).
homebot's arm alone cannot tell the pitch: the handle turns between the fingers (only
their torsional friction and the grip pocket's lips hold it), so the hand's pitch lags
and even opposes the table's, and the forces at the robot's end hardly change with the
pitch (the table's weight is shared by the horizontal distances of its ends from its
centre of mass, which a few degrees of pitch change by a fraction of a per cent).
So ``TablePitch`` looks: a vertical fan of laser rays from the top of the torso, along
the direction the hand points, falls on the table's top beyond the hand. The points on
the top, in that vertical plane, lie on a line whose slope is the table's pitch. The
fit is a least-squares line with outliers (the floor past the far edge, the far edge
itself) dropped; between scans, or when too few rays hit the top, the last pitch holds.
Everything here comes from what the robot's drivers report: the torso's height, the
hand's pose by forward kinematics and the laser's ranges.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["TablePitch"]

#: Where the laser sits on the robot, base frame, with the torso lift at zero (the top of
#: the torso column: Cosero's head camera looks down from about there).
MOUNT = np.array([0.0, 0.0, 1.05])


class TablePitch:
    """The carried table's pitch (rad, positive: the far end higher than the robot's).

    Args:
        down: the fan's rays, in degrees below the horizontal (the table's top from the
            hand to two metres beyond it, whether the person holds it high or low).
        beyond: metres past the hand where the table's top may begin.
        band: metres below and above the hand's height a point of the top may lie.
        min_points: rays that must fall on the top for a new fit.
    """

    def __init__(self, *, down: tuple[float, float, float] = (2.0, 30.0, 0.25),
                 beyond: float = 0.04, band: tuple[float, float] = (0.25, 0.8),
                 min_points: int = 8) -> None:
        first, last, step = down
        self.angles = np.radians(np.arange(first, last + step / 2, step))
        self.beyond, self.band, self.min_points = beyond, band, min_points
        self.pitch = 0.0  #: the last fitted pitch
        self.points = 0  #: how many rays fell on the top in the last fit

    def mount(self, torso: float) -> np.ndarray:
        """The laser's position (base frame) at the torso lift's height ``torso``."""
        mount: np.ndarray = MOUNT + np.array([0.0, 0.0, torso])
        return mount

    def directions(self, hand_rotation: np.ndarray) -> np.ndarray:
        """The fan's unit rays (base frame): down at ``angles``, towards where the hand's
        x axis points in the floor's plane."""
        forward = np.asarray(hand_rotation, dtype=float)[:2, 0]
        heading = math.atan2(float(forward[1]), float(forward[0]))
        c = np.cos(self.angles)
        return np.column_stack((c * math.cos(heading), c * math.sin(heading),
                                -np.sin(self.angles)))

    def update(self, torso: float, hand_position: np.ndarray, hand_rotation: np.ndarray,
               ranges: np.ndarray) -> float:
        """The pitch from one scan (``ranges`` along ``directions(hand_rotation)`` from
        ``mount(torso)``); the last pitch if the scan shows too little of the top."""
        rays = self.directions(hand_rotation)
        ranges = np.asarray(ranges, dtype=float)
        seen = np.isfinite(ranges)
        points = self.mount(torso) + rays[seen] * ranges[seen, None]
        hand = np.asarray(hand_position, dtype=float)
        along_x = rays[0, :2] / max(1e-9, float(np.linalg.norm(rays[0, :2])))
        run = (points[:, :2] - hand[:2]) @ along_x  # horizontal distance past the hand
        rise = points[:, 2] - hand[2]
        low, high = self.band
        keep = (run > self.beyond) & (rise > -low) & (rise < high)
        run, rise = run[keep], rise[keep]
        for _ in range(3):  # refit without what lies off the line (the edge, the floor)
            if len(run) < self.min_points:
                return self.pitch
            slope, offset = np.polyfit(run, rise, 1)
            residual = np.abs(rise - (slope * run + offset))
            inliers = residual < max(0.015, 2.5 * float(np.std(residual)))
            if bool(inliers.all()):
                break
            run, rise = run[inliers], rise[inliers]
        if len(run) < self.min_points:
            return self.pitch
        slope, _ = np.polyfit(run, rise, 1)
        self.pitch, self.points = math.atan(float(slope)), len(run)
        return self.pitch
