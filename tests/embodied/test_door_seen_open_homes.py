"""door_seen_open on ordinary doorways: 0.8 m doors seen from the side, half open, with
someone or something beside them, and shut. The sweeps are cast here in a small plan of
two rooms (shapely), the way the simulator's laser sees it: 271 beams over 270 degrees."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, Point, box
from shapely.ops import unary_union

from homebot.embodied.doors import door_seen_open
from homebot.geometry import Pose
from homebot.robot import LaserScan

_WIDTH = 0.8  #: the doorway, metres, centred at (0, 0) in the wall y = 0
_CENTRE = (0.0, 0.0)
_NORMAL = (0.0, -1.0)  #: across the wall, towards the robot's room
_BEAMS, _FIELD, _RANGE = 271, math.radians(270.0), 10.0


def _walls() -> list[object]:
    half = _WIDTH / 2
    return [box(-3.0, -0.05, -half, 0.05), box(half, -0.05, 3.0, 0.05),  # the wall
            box(-3.1, -3.0, -3.0, 4.0), box(3.0, -3.0, 3.1, 4.0),        # side walls
            box(-3.0, 4.0, 3.0, 4.1), box(-3.0, -3.1, 3.0, -3.0)]        # far and near


def _leaf(opening_deg: float) -> object:
    """The leaf hinged at the left jamb, swung ``opening_deg`` into the far room."""
    hinge = (-_WIDTH / 2, 0.0)
    angle = math.radians(opening_deg)
    tip = (hinge[0] + _WIDTH * math.cos(angle), hinge[1] + _WIDTH * math.sin(angle))
    return LineString([hinge, tip]).buffer(0.02)


def _sweep(pose: Pose, *extra: object) -> LaserScan:
    solid = unary_union([*_walls(), *extra])
    angle_min = -_FIELD / 2
    increment = _FIELD / (_BEAMS - 1)
    ranges = np.full(_BEAMS, np.inf)
    for i in range(_BEAMS):
        heading = pose.theta + angle_min + i * increment
        end = (pose.x + _RANGE * math.cos(heading), pose.y + _RANGE * math.sin(heading))
        hit = LineString([(pose.x, pose.y), end]).intersection(solid)
        if not hit.is_empty:
            ranges[i] = Point(pose.x, pose.y).distance(hit)
    return LaserScan(stamp=0.0, angle_min=angle_min, angle_increment=increment,
                     range_min=0.05, range_max=_RANGE, ranges=ranges)


def _seen(pose: Pose, *extra: object) -> bool | None:
    return door_seen_open(_sweep(pose, *extra), pose, _CENTRE, _NORMAL, _WIDTH)


_FACING = Pose(0.0, -0.6, math.pi / 2)  # stopped 0.6 m before the door, facing it


def test_an_open_door_straight_ahead_is_read_open() -> None:
    assert _seen(_FACING) is True


def test_a_shut_door_is_read_shut() -> None:
    assert _seen(_FACING, _leaf(0.0)) is False


@pytest.mark.parametrize("opening_deg", [50.0, 70.0, 90.0])
def test_a_half_open_passable_door_is_read_open(opening_deg: float) -> None:
    # a 0.8 m leaf swung 50 degrees leaves 0.61 m between its face and the far jamb
    assert _seen(_FACING, _leaf(opening_deg)) is True


@pytest.mark.parametrize("pose", [
    Pose(-1.2, -0.5, -0.6),            # beside the door, looking away: the doorway at ~120 deg
    Pose(1.5, -0.4, math.pi),          # along the wall, the doorway at the field's side
    Pose(0.9, -1.8, math.pi / 2 + 1.9),  # the doorway near the edge of the field of view
])
def test_an_open_door_at_the_edge_of_the_view_is_not_read_shut(pose: Pose) -> None:
    assert _seen(pose) is not False


def test_an_open_door_seen_at_a_slant_is_read_open() -> None:
    assert _seen(Pose(-1.5, -1.0, 0.6)) is True


@pytest.mark.parametrize("beside", [
    Point(0.65, -0.3).buffer(0.22),          # someone standing beside the jamb
    Point(-0.55, -0.45).buffer(0.2),         # someone near the hinge side
    box(0.45, -0.6, 1.25, -0.2),             # a shoe cabinet beside the door
])
def test_an_open_door_with_someone_or_something_beside_it_is_read_open(beside: object) -> None:
    assert _seen(_FACING, beside) is True
    assert _seen(Pose(0.0, -1.4, math.pi / 2), beside) is True


def test_a_shut_door_with_someone_beside_it_is_read_shut() -> None:
    assert _seen(_FACING, _leaf(0.0), Point(0.65, -0.3).buffer(0.22)) is False
