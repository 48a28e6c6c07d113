"""pyrobosim's poses, footprints and hallways redone on shapely geometry."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import Polygon, box

from homebot.world.pyrobosim_geometry import (
    PlanarPose,
    PoseFormatError,
    aligned_box,
    corridor,
    free_point,
    parse_pose,
    place_footprint,
    shared_edge,
    simple_footprint,
    straight_hallway,
)


@pytest.mark.parametrize(("written", "expected"), [
    ([1, 2], (1.0, 2.0, 0.0, False)),
    ([1, 2, 0.5], (1.0, 2.0, 0.0, False)),  # the third number is z
    ([1, 2, 0, 0.7], (1.0, 2.0, 0.7, False)),
    ([1, 2, 0, 0.1, 0, 0.7], (1.0, 2.0, 0.7, True)),  # roll, pitch, yaw
    ([1, 2, 0, math.cos(0.35), 0, 0, math.sin(0.35)], (1.0, 2.0, 0.7, False)),  # w x y z
    ({"position": {"x": 1, "y": 2}, "rotation_eul": {"yaw": 90, "angle_units": "degrees"}},
     (1.0, 2.0, math.pi / 2, False)),
    ({"position": {"x": 1}, "rotation_quat": {"w": 0.7071, "z": -0.7071}},
     (1.0, 0.0, -math.pi / 2, False)),
    ({"position": {"y": 3}}, (0.0, 3.0, 0.0, False)),
])
def test_every_pose_form_pyrobosim_reads(written: object, expected: tuple[float, ...]) -> None:
    pose = parse_pose(written)
    assert (pose.x, pose.y, pose.yaw, pose.tilted) == pytest.approx(expected, abs=1e-4)


@pytest.mark.parametrize("written", [
    [1], [1, 2, 3, 4, 5], ["a", 2], "here", {"position": [1, 2]},
    {"rotation_eul": {"yaw": 1, "angle_units": "turns"}},
])
def test_a_pose_in_no_form_says_the_forms(written: object) -> None:
    with pytest.raises(PoseFormatError):
        parse_pose(written)


def test_a_relative_pose_adds_position_and_yaw_without_turning_the_offset() -> None:
    # pyrobosim's get_pose_relative_to: the offset is not turned by the anchor's yaw.
    pose = parse_pose({"position": {"x": 1.0}, "relative_to": "table"})
    assert pose.relative_to == "table"
    placed = pose.after(PlanarPose(5.0, 5.0, math.pi / 2))
    assert (placed.x, placed.y, placed.yaw) == pytest.approx((6.0, 5.0, math.pi / 2))


def test_a_footprint_moves_to_its_pose_then_turns_about_it() -> None:
    polygon, height = simple_footprint({"type": "box", "dims": [2.0, 1.0], "offset": [1.0, 0.0],
                                        "height": 0.5})
    assert polygon.bounds == pytest.approx((0.0, -0.5, 2.0, 0.5)) and height == 0.5
    placed = place_footprint(polygon, PlanarPose(10.0, 0.0, math.pi / 2))
    assert placed.bounds == pytest.approx((9.5, 0.0, 10.5, 2.0))


@pytest.mark.parametrize("footprint", [
    {"type": "box", "dims": [1]}, {"type": "polygon", "coords": [[0, 0], [1, 1]]},
    {"type": "circle"}, {"type": "mesh"}, {"type": "box", "dims": [1, 1], "offset": 2},
    {"type": "polygon", "coords": [[0, 0], [1, 1], [1, 0], [0, 1]]},  # crosses itself
])
def test_a_footprint_homebot_cannot_read_is_refused(footprint: dict[str, object]) -> None:
    with pytest.raises(PoseFormatError):
        simple_footprint(footprint)


def test_an_angle_hallway_keeps_the_projected_length_and_an_offset_shifts_it() -> None:
    # From (0, 0) towards (4, 3) at angle 0: 4 m long (5 m projected), shifted 1 m left.
    (start, end) = straight_hallway((0.0, 0.0), (4.0, 3.0), 1.0, 0.0)
    assert (*start, *end) == pytest.approx((0.0, 1.0, 4.0, 1.0))
    auto = straight_hallway((0.0, 0.0), (0.0, 2.0), 0.5, None)  # north, shifted west
    assert (*auto[0], *auto[1]) == pytest.approx((-0.5, 0.0, -0.5, 2.0))
    floor = corridor(auto, 0.6)
    assert floor.bounds == pytest.approx((-0.8, 0.0, -0.2, 2.0))  # flat ends


def test_shared_edge_is_the_stretch_two_outlines_have_in_common() -> None:
    edge = shared_edge(box(0, 0, 2, 2), box(2, 0.5, 4, 1.5))
    assert edge is not None and edge.length == pytest.approx(1.0, abs=1e-5)
    assert shared_edge(box(0, 0, 1, 1), box(2, 2, 3, 3)) is None


def test_a_turned_footprint_becomes_a_box_that_fits_its_room() -> None:
    table = Polygon([(-0.6, -0.3), (0.6, -0.3), (0.6, 0.3), (-0.6, 0.3)])
    room = box(0, 0, 3, 3)
    # A quarter turn fits whole; 30° gives the box around it.
    shape, kept = aligned_box(table, PlanarPose(1.5, 1.5, math.pi / 2), room, [])
    assert shape.bounds == pytest.approx((1.2, 0.9, 1.8, 2.1)) and kept == 1.0
    shape, kept = aligned_box(table, PlanarPose(1.5, 1.5, math.radians(30)), room, [])
    assert kept == 1.0 and shape.area > table.area
    # Against a wall, or against other furniture, it shrinks about its centre.
    shape, kept = aligned_box(table, PlanarPose(0.5, 1.5, 0.0), room, [])
    assert room.covers(shape) and kept == pytest.approx(0.5 / 0.6, abs=1e-3)
    shape, kept = aligned_box(table, PlanarPose(1.5, 1.5, 0.0), room, [box(2.0, 0, 3, 3)])
    assert shape.bounds[2] == pytest.approx(2.0, abs=1e-4)


def test_a_free_point_is_the_target_or_the_nearest_point_of_the_area() -> None:
    area = box(0, 0, 1, 1)
    assert free_point(area, (0.5, 0.5)) == (0.5, 0.5)
    assert free_point(area, (2.0, 0.5)) == pytest.approx((1.0, 0.5))
    assert free_point(Polygon(), (0.0, 0.0)) is None
