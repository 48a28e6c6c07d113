"""Eight orientation sectors: a partition of directions; intrinsic and relative reference."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from homebot.space.orientation import (
    ORIENTATIONS,
    SECTOR,
    intrinsic_angle,
    orientation_category,
    orientation_memberships,
    relative_angle,
    side_degree,
)

angles = st.floats(min_value=-20.0, max_value=20.0, allow_nan=False)


@given(angles)
def test_sector_memberships_sum_to_one_and_only_neighbours_overlap(angle: float) -> None:
    degrees = orientation_memberships(angle)
    assert math.isclose(sum(degrees), 1.0)
    holding = [index for index, degree in enumerate(degrees) if degree > 1e-12]
    assert len(holding) <= 2
    if len(holding) == 2:
        assert (holding[1] - holding[0]) % len(ORIENTATIONS) in (1, len(ORIENTATIONS) - 1)


@given(st.integers(min_value=0, max_value=7))
def test_halfway_between_sectors_both_hold_half(index: int) -> None:
    degrees = orientation_memberships((index + 0.5) * SECTOR)
    assert degrees[index] == pytest.approx(0.5)
    assert degrees[(index + 1) % 8] == pytest.approx(0.5)
    assert orientation_category(index * SECTOR) == ORIENTATIONS[index]


def test_intrinsic_reference_follows_the_front_side() -> None:
    sofa, facing_north = (0.0, 0.0), math.pi / 2
    assert orientation_category(intrinsic_angle((0.0, 1.0), sofa, facing_north)) == "front"
    assert orientation_category(intrinsic_angle((0.0, -1.0), sofa, facing_north)) == "back"
    assert orientation_category(intrinsic_angle((-1.0, 0.0), sofa, facing_north)) == "left"
    assert orientation_category(intrinsic_angle((1.0, 1.0), sofa, facing_north)) == "front_right"


def test_relative_reference_is_the_viewers_left_and_far_side() -> None:
    viewer, bowl = (0.0, -1.0), (0.0, 0.0)  # the viewer looks north at the bowl
    assert orientation_category(relative_angle((0.0, 0.3), bowl, viewer)) == "back"
    assert orientation_category(relative_angle((0.0, -0.3), bowl, viewer)) == "front"
    assert orientation_category(relative_angle((-0.3, 0.0), bowl, viewer)) == "left"
    assert orientation_category(relative_angle((0.3, 0.0), bowl, viewer)) == "right"


@given(angles)
def test_side_degree_is_one_at_the_centre_and_falls_to_zero_at_ninety_degrees(
        angle: float) -> None:
    off = abs((angle - math.pi / 2 + math.pi) % (2 * math.pi) - math.pi)
    assert side_degree(angle, "left") == pytest.approx(max(0.0, 1.0 - off / (math.pi / 2)),
                                                       abs=1e-9)
