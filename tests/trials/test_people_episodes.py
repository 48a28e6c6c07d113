"""The people-perception figures of ``bench perception``, on the smallest sizes, judged by truth."""

from __future__ import annotations

import pytest

pytest.importorskip("motmetrics")

from homebot.trials.people import (
    lateration_figures,
    people_figures,
    pointing_figures,
)


def test_people_figures_come_from_motmetrics_over_the_crowd_scenes() -> None:
    figures = people_figures(2, 1)
    assert figures["scenes"] == 1 and figures["person_frames"] == 2 * 200
    assert 0.7 <= figures["mota"] <= 1.0
    assert figures["switches_per_100_track_seconds"] >= 0.0
    assert figures["track_seconds"] == pytest.approx(40.0)
    assert set(figures["posture_right"]) == {"standing", "sitting", "lying"}


def test_pointing_and_lateration_figures() -> None:
    pointing = pointing_figures(3, 40)
    assert pointing["trials"] == 40 and pointing["right_placement"] >= 0.85
    assert pointing["gestures_classified_as"]["stop"].get("stop", 0) >= 45
    tags = lateration_figures(4, 40)
    assert tags["median_error_smoothed_m"] < tags["median_error_one_beacon_m"]
    assert tags["right_placement_in_first_three"] >= 0.8
