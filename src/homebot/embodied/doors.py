"""Whether a door is open, from the laser: do its beams pass through the doorway?

A shut door's leaf stands in the wall's line, so every beam that crosses the
doorway ends on that line; through an open door most beams go on into the next
room. Someone standing in an open doorway stops only the beams that meet them,
and a person filling the doorway stands out of the line where a leaf is flat.
Beams that end well before the line (something in front of the door, a leaf
swung towards the robot) tell nothing.

Whether an open doorway lets the robot through is geometry (``way_through``):
a leaf left half open, a coat rack beside the jamb or someone standing in the
doorway are all returns, and the robot fits through when some straight way
across the doorway keeps its radius from every one of them and from the jambs.

A leaf left barely ajar keeps the robot out as a shut one does, but the beams
pass its gap, so the doorway reads open. It is told from someone standing there
by its shape (``leaf_barely_ajar``): a straight line anchored at a jamb, where a
person is a body or a pair of legs, a few tenths of a metre across.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from homebot.geometry import Pose, rays_cross_line
from homebot.robot import LaserScan

__all__ = ["WayThrough", "door_seen_open", "leaf_barely_ajar", "way_through"]

_JAMB = 0.08  #: metres inside each jamb where beams are not counted
_PAST_THE_LINE = 0.1  #: metres past the wall's middle line: a beam went through
_IN_FRONT = 0.35  #: metres in front of the line where returns are the door or someone in it
_IN_LINE = 0.12  #: metres in front of the line within which a return may be a shut leaf
_LEAF_IN_FRONT = 1.0  #: metres in front of the line a leaf swung towards the robot reaches
_SLANTED_LEAF = 0.15  #: metres of depth over which such a leaf's returns spread at least
_BODY = 0.06  #: metres a person stands out of a leaf's face
_THROUGH = 2  #: beams through the doorway that show it open
_SHUT = 3  #: beams at the door that show it shut (or someone in it)
#: metres along a way through, either side of the wall's line, to its ends: 0.45 m fits in
#: a 1.0 m corridor; a narrow way ends 0.7 m out where that fits, clear of a leaf's tip
_SHORT_REACH, _LONG_REACH = 0.45, 0.7
_ROOM_TO_GO_ON = 0.03  #: metres of room a narrow way may give up to end 0.7 m out
_ROOMY = 0.1  #: metres to spare a side on a straight way through: no narrow doorway
_SLANTED = 0.1  #: radians: a way through slanted more than this is a narrow one
_SLANTS = np.radians(np.arange(-60.0, 61.0, 5.0))  #: ways through, from straight across
_OFFSET_STEP = 0.02  #: metres between the ways through tried along the doorway
_WALL_STEP = 0.02  #: metres between the points standing for the wall beside the doorway
_PREFER_STRAIGHT = 0.02  #: metres of room given up per radian of slant and metre off centre
# A leaf barely ajar: returns on a straight line from a jamb into the doorway's swing.
_LEAF_FROM_HINGE = (0.1, 0.9)  #: its returns' distances from the hinge, in door widths
_LEAF_FIT = 0.03  #: metres from the line through the hinge a leaf's returns lie within
_LEAF_RETURNS = 6  #: returns on that line at least
_LEAF_SHARE = 0.7  #: of the returns in the swing, the share on that line at least
_LEAF_SEEN = 0.35  #: door widths of the leaf its returns span at least, unbroken ...
_LEAF_ANCHOR = 0.25  #: ... from this many metres of the hinge at most (a jamb may hide it)
_LEAF_GAP = 0.1  #: metres between neighbouring returns along a leaf at most (legs leave more)
_LEAF_TIP_ROOM = 0.05  #: metres beyond the robot's width the leaf's tip must leave


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
    if np.count_nonzero(at_the_door >= -_IN_LINE) < _SHUT:
        # Nothing in the wall's line, where a shut leaf stands: what the beams meet stands
        # in front of the doorway. Slanted across it, it is the leaf swung towards the
        # robot (the door is open); else it hides the doorway.
        in_front = gap[(gap < -_IN_LINE) & (gap >= -_LEAF_IN_FRONT)]
        if len(in_front) >= _SHUT and float(np.ptp(in_front)) >= _SLANTED_LEAF:
            return True
        return None
    # a leaf is flat; someone filling the doorway stands out of it, towards the robot
    face = float(np.percentile(at_the_door, 75))
    standing_out = at_the_door < face - _BODY
    return bool(np.count_nonzero(standing_out) >= _SHUT)


def leaf_barely_ajar(points: np.ndarray, centre: tuple[float, float],
                     normal: tuple[float, float], width: float, radius: float) -> bool:
    """Whether the returns ``points`` ((n, 2), on the map) show a door leaf standing
    barely ajar across the doorway: a straight line from one jamb, turned so little from
    the wall that its tip leaves the other jamb less room than the robot's width (a disc
    of ``radius``) needs. Someone standing in the doorway is no straight line from a
    jamb; a leaf swung well open leaves room at its tip.

    Args:
        centre: the middle of the doorway on the map; ``normal`` a unit vector across
            the wall there; ``width`` the doorway's, metres.
    """
    n = np.asarray(normal, dtype=float) / float(np.hypot(*normal))
    relative_to_centre = np.asarray(points, dtype=float).reshape(-1, 2) - np.asarray(centre)
    for side in (1.0, -1.0):
        # the hinge at one jamb, the doorway running from it towards the other
        towards = side * np.array([n[1], -n[0]])
        relative = relative_to_centre + towards * width / 2
        distance = np.hypot(relative[:, 0], relative[:, 1])
        swing = (distance >= _LEAF_FROM_HINGE[0] * width) & \
            (distance <= _LEAF_FROM_HINGE[1] * width) & (relative @ towards > 0)
        if np.count_nonzero(swing) < _LEAF_RETURNS:
            continue
        inside = relative[swing]
        angle = float(np.median(np.arctan2(inside @ n, inside @ towards)))
        direction = np.cos(angle) * towards + np.sin(angle) * n
        off_the_line = np.abs(inside @ np.array([-direction[1], direction[0]]))
        on_the_line = off_the_line <= _LEAF_FIT
        if np.count_nonzero(on_the_line) < _LEAF_RETURNS or \
                float(np.mean(on_the_line)) < _LEAF_SHARE:
            continue
        # one unbroken run from by the hinge: a pair of legs in line leaves a gap
        along = np.sort(inside[on_the_line] @ direction)
        breaks = np.flatnonzero(np.diff(along) > _LEAF_GAP)
        run_end = along[breaks[0]] if len(breaks) else along[-1]
        if along[0] > _LEAF_ANCHOR or run_end - along[0] < _LEAF_SEEN * width:
            continue
        tip_to_jamb = 2 * width * np.sin(abs(angle) / 2)
        if tip_to_jamb < 2 * radius + _LEAF_TIP_ROOM:
            return True
    return False


@dataclass(frozen=True, slots=True)
class WayThrough:
    """A straight way across a doorway, on the map: from ``entry`` on the side the
    door's normal points to, to ``exit`` on the other, each up to 0.7 m along it from the
    wall's line; ``room`` metres to spare between the disc on the way and the nearest
    return or jamb; ``slant`` radians from straight across."""

    entry: tuple[float, float]
    exit: tuple[float, float]
    room: float
    slant: float
    offset: float  #: metres from the doorway's middle, along the wall, where it crosses

    @property
    def narrow(self) -> bool:
        """Little room to spare, or slanted (past a leaf): to be lined up with and driven
        along, rather than left to the local planner's margins."""
        return self.room < _ROOMY or abs(self.slant) >= _SLANTED


def way_through(points: np.ndarray, centre: tuple[float, float], normal: tuple[float, float],
                width: float, wall_thickness: float, radius: float) -> WayThrough | None:
    """The straight way across the doorway, from the ``normal``'s side to the other,
    with the most room round a disc of ``radius``: past ``points`` (laser returns on the
    map, (n, 2)) and the jambs; None when no way leaves the disc room.

    The ways tried cross the wall's line anywhere in the doorway, straight or slanted
    up to 60 degrees (past a leaf left half open the way runs along the leaf); the
    disc is swept along each from end to end, 0.45 m either side of the wall's line,
    or for a narrow way 0.7 m where that leaves nearly as much room.
    """
    short = _way_through(points, centre, normal, width, wall_thickness, radius, _SHORT_REACH)
    if short is None or not short.narrow:
        return short
    # A narrow way: the farther it runs on, the clearer of a leaf's tip the robot comes
    # out, unless running on costs much of what little room there is.
    long = _way_through(points, centre, normal, width, wall_thickness, radius, _LONG_REACH)
    return long if long is not None and long.room >= short.room - _ROOM_TO_GO_ON else short


def _way_through(points: np.ndarray, centre: tuple[float, float],
                 normal: tuple[float, float], width: float, wall_thickness: float,
                 radius: float, reach: float) -> WayThrough | None:
    """``way_through`` with its ends ``reach`` metres either side of the wall's line."""
    nx, ny = np.asarray(normal, dtype=float) / float(np.hypot(*normal))
    tx, ty = -ny, nx
    half = width / 2
    relative = np.asarray(points, dtype=float).reshape(-1, 2) - np.asarray(centre)
    along = relative @ np.array([tx, ty])
    across = relative @ np.array([nx, ny])
    # the wall either side of the doorway, its faces and the jambs, as the map has it
    beyond = np.arange(half, half + reach + radius + _WALL_STEP, _WALL_STEP)
    faces = np.arange(-wall_thickness / 2, wall_thickness / 2 + 1e-9, _WALL_STEP)
    wall_along = np.concatenate([beyond, -beyond, beyond, -beyond,
                                 np.full(len(faces), half), np.full(len(faces), -half)])
    wall_across = np.concatenate([np.full(2 * len(beyond), -wall_thickness / 2),
                                  np.full(2 * len(beyond), wall_thickness / 2), faces, faces])
    near = (np.abs(across) <= reach + 2 * radius) & \
        (np.abs(along) <= half + reach + radius)
    along = np.concatenate([along[near], wall_along])
    across = np.concatenate([across[near], wall_across])
    offsets = np.arange(-half + radius, half - radius + 1e-9, _OFFSET_STEP)
    best: tuple[float, float, float, float] | None = None  # (score, room, slant, offset)
    for slant in _SLANTS:
        sine, cosine = float(np.sin(slant)), float(np.cos(slant))
        # per way (row) and point (column): distance from the way, and how far along it
        shifted = along[None, :] - offsets[:, None]
        off_the_way = np.abs(shifted * cosine - across[None, :] * sine)
        on_the_way = shifted * sine + across[None, :] * cosine
        # the disc swept from end to end: a point past an end is as far as from that end
        past_the_end = np.maximum(np.abs(on_the_way) - reach, 0.0)
        room = np.hypot(off_the_way, past_the_end).min(axis=1)
        # the most room, and of ways with nearly as much, the straightest and most central
        score = room - _PREFER_STRAIGHT * (abs(float(slant)) + np.abs(offsets))
        k = int(np.argmax(score))
        if room[k] >= radius and (best is None or score[k] > best[0]):
            best = (float(score[k]), float(room[k]), float(slant), float(offsets[k]))
    if best is None:
        return None
    _, room, slant, offset = best
    # the way's direction, from the normal's side across the wall
    dx = -(nx * np.cos(slant) + tx * np.sin(slant))
    dy = -(ny * np.cos(slant) + ty * np.sin(slant))
    cx, cy = centre[0] + tx * offset, centre[1] + ty * offset
    return WayThrough((float(cx - dx * reach), float(cy - dy * reach)),
                      (float(cx + dx * reach), float(cy + dy * reach)),
                      room - radius, slant, offset)
