"""Fuzzy distance memberships: a partition, 0.5 at boundaries, scaled by the frame."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from homebot.space.distance import (
    BOUNDARIES,
    CENTRES,
    DISTANCES,
    at_most,
    closeness,
    distance_category,
    distance_memberships,
    is_distance,
)

distances = st.floats(min_value=0.0, max_value=100.0, allow_nan=False)
scales = st.floats(min_value=0.05, max_value=50.0, allow_nan=False)


@given(distances, scales)
def test_memberships_sum_to_one_and_at_most_two_hold(distance: float, scale: float) -> None:
    degrees = distance_memberships(distance, scale)
    assert math.isclose(sum(degrees), 1.0)
    assert all(0.0 <= degree <= 1.0 for degree in degrees)
    holding = [index for index, degree in enumerate(degrees) if degree > 0]
    assert len(holding) <= 2
    if len(holding) == 2:  # only neighbours overlap
        assert holding[1] == holding[0] + 1


@given(scales, st.integers(min_value=0, max_value=len(BOUNDARIES) - 1))
def test_at_a_boundary_the_two_neighbours_hold_half_each(scale: float, index: int) -> None:
    degrees = distance_memberships(BOUNDARIES[index] * scale, scale)
    assert degrees[index] == pytest.approx(0.5)
    assert degrees[index + 1] == pytest.approx(0.5)


@given(scales, st.integers(min_value=0, max_value=len(CENTRES) - 1))
def test_at_a_centre_one_category_holds_fully(scale: float, index: int) -> None:
    assert distance_category(CENTRES[index] * scale, scale) == DISTANCES[index]
    assert is_distance(CENTRES[index] * scale, DISTANCES[index], scale) == pytest.approx(1.0)


@given(distances, scales, st.floats(min_value=0.1, max_value=10.0))
def test_the_scale_of_the_frame_scales_the_categories(distance: float, scale: float,
                                                      factor: float) -> None:
    """Memberships depend on distance / scale only: a room ``factor`` times larger than a
    table calls ``factor`` times the distance by the same name."""
    small = distance_memberships(distance, scale)
    large = distance_memberships(distance * factor, scale * factor)
    assert large == pytest.approx(small, abs=1e-9)


def test_close_on_a_table_is_not_close_in_a_room() -> None:
    table, room = math.hypot(1.2, 0.8), math.hypot(5.0, 4.0)
    assert distance_category(0.15, table) == "close"
    assert distance_category(0.15, room) == "very_close"
    assert distance_category(0.45, room) == "close"
    assert distance_category(0.45, table) == "medium"


@given(distances, distances, scales)
def test_closeness_never_grows_with_distance(first: float, second: float, scale: float) -> None:
    near, far = sorted((first, second))
    assert closeness(near, scale) >= closeness(far, scale) - 1e-12
    if far < scale:
        assert far - near < 1e-9 or closeness(near, scale) > closeness(far, scale)


@given(distances, scales)
def test_at_most_adds_the_nearer_categories(distance: float, scale: float) -> None:
    degrees = distance_memberships(distance, scale)
    assert at_most(distance, "close", scale) == pytest.approx(degrees[0] + degrees[1])
    assert at_most(distance, "very_far", scale) == pytest.approx(1.0)


def test_unknown_category_and_bad_scale_are_refused() -> None:
    with pytest.raises(ValueError, match="unknown distance category"):
        is_distance(1.0, "nearby")
    with pytest.raises(ValueError, match="greater than 0"):
        distance_memberships(1.0, 0.0)
