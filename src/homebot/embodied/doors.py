"""Whether a door is open, from the laser: do its beams pass through the doorway?

A shut door's leaf stands in the wall's line, so every beam that crosses the
doorway ends on that line; through an open door most beams go on into the next
room. Someone standing in an open doorway stops only the beams that meet them,
and a person filling the doorway stands out of the line where a leaf is flat.
Beams that end well before the line (something in front of the door) tell nothing.
"""

from __future__ import annotations

import numpy as np

from homebot.geometry import Pose, rays_cross_line
from homebot.robot import LaserScan

__all__ = ["door_seen_open"]

_JAMB = 0.08  #: metres inside each jamb where beams are not counted
_PAST_THE_LINE = 0.1  #: metres past the wall's middle line: a beam went through
_IN_FRONT = 0.35  #: metres in front of the line where returns are the door or someone in it
_BODY = 0.06  #: metres a person stands out of a leaf's face
_THROUGH = 2  #: beams through the doorway that show it open
_SHUT = 3  #: beams at the door that show it shut (or someone in it)


def door_seen_open(scan: LaserScan, pose: Pose, centre: tuple[float, float],
                   normal: tuple[float, float], width: float) -> bool | None:
    """True (open), False (shut) or None (the laser cannot tell: the doorway is out of
    view, or hidden behind something nearer).

    Args:
        scan: the latest sweep; ``pose`` where the robot is (its estimate).
        centre: the middle of the doorway on the map; ``normal`` a unit vector across
            the wall there; ``width`` the doorway's, metres.
    """
    origin = pose.apply(scan.mount.x, scan.mount.y)
    angles = scan.angles() + scan.mount.theta + pose.theta
    rays = np.column_stack((np.cos(angles), np.sin(angles)))
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
    # where each ray meets the door's line: u metres along the ray, s along the wall
    u, s = rays_cross_line(origin, rays, centre, normal)
    facing = rays @ np.asarray(normal)
    crosses = (np.abs(facing) > 1e-6) & (u > 0) & (u < scan.range_max) & (
        np.abs(s) <= width / 2 - _JAMB)
    # how far past the line each crossing beam ends (negative: in front of it)
    gap = ranges[crosses] - u[crosses]
    if int(np.count_nonzero(gap > _PAST_THE_LINE)) >= _THROUGH:
        return True
    at_the_door = gap[(gap >= -_IN_FRONT) & (gap <= _PAST_THE_LINE)]
    if len(at_the_door) < _SHUT:
        return None
    # a leaf is flat; someone filling the doorway stands out of it, towards the robot
    face = float(np.percentile(at_the_door, 75))
    standing_out = at_the_door < face - _BODY
    return bool(np.count_nonzero(standing_out) >= _SHUT)
