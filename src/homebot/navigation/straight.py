"""Driving a straight line at a crawl: the way through a doorway a leaf or furniture narrows.

Past a door's leaf left half open, a 0.8 m doorway leaves a 0.5 m robot a few
centimetres a side on one straight way, along the leaf. Stage 2 keeps a safety
margin from walls and furniture that such a way does not have; a person
passing a narrow door does what this does instead: line up with the way, then
go straight along it slowly, watching that nothing comes into the footprint's
path, and stop if something does.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from homebot.geometry import Pose, wrap_angle
from homebot.robot import Body, Twist

__all__ = ["drive_straight"]

_CRAWL = 0.15  #: m/s along the way
_LOOK_AHEAD = 0.15  #: metres ahead of the footprint that must stay free
_STEER = 1.5  #: rad/s of turn per metre off the line and per radian off its heading
_ARRIVED = 0.03  #: metres short of the end where the robot counts as there
_STRAY = 0.12  #: metres off the line at which the robot stops (lost the way)
_ALIGNED = 0.1  #: radians off the way's heading within which the robot drives on


def drive_straight(body: Body, localise: Callable[[], Pose], start: tuple[float, float],
                   end: tuple[float, float]) -> bool:
    """From about ``start``, facing ``end``, drive straight to ``end`` along the line
    between them; False (the base at rest) when a laser return comes into the
    footprint's path, the robot strays off the line, or it takes more than twice the
    time the line needs.
    """
    length = math.dist(start, end)
    if length < 1e-6:
        return True
    ux, uy = (end[0] - start[0]) / length, (end[1] - start[1]) / length
    heading = math.atan2(uy, ux)
    ticks = int(2 * (length / _CRAWL + 2.0) / body.tick_period)
    arrived = False
    for _ in range(ticks):
        pose = localise()
        dx, dy = pose.x - start[0], pose.y - start[1]
        along = dx * ux + dy * uy
        off = -dx * uy + dy * ux  # left of the line: positive
        if along >= length - _ARRIVED:
            arrived = True
            break
        if abs(off) > _STRAY:
            break
        error = wrap_angle(heading - pose.theta)
        turn = _STEER * (error - off)
        # turned along the way first, on the spot; the strip ahead is the way's then
        speed = _CRAWL if abs(error) < _ALIGNED else 0.0
        # the strip ahead, up to where the footprint ends at the line's end
        ahead = min(_LOOK_AHEAD, length - along) + body.radius
        if speed and not _path_free(body, ahead, body.radius):
            break
        body.command_velocity(Twist(min(speed, length - along + 0.02), 0.0,
                                    max(-body.limits.angular, min(body.limits.angular, turn))))
        body.tick()
    body.command_velocity(Twist())
    body.tick()
    return arrived


def _path_free(body: Body, ahead: float, half_width: float) -> bool:
    """No return in the strip in front of the base, ``ahead`` metres long from its
    centre and ``2 * half_width`` wide (the base's frame)."""
    points = body.scan().points()
    if not len(points):
        return True
    in_front = (points[:, 0] > 0.0) & (points[:, 0] < ahead) & \
        (np.abs(points[:, 1]) < half_width)
    return not bool(in_front.any())
