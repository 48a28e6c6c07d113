"""Bluetooth lateration: least squares with an unknown tag power, smoothing, the placement hint."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.perception.lateration import TagLocaliser, laterate, placement_hint
from homebot.sim.radio import rssi_readings

RECEIVERS = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]])


@pytest.mark.parametrize("power", [-70.0, -55.0])
def test_noise_free_readings_give_the_position_whatever_the_tags_power(power: float) -> None:
    tag = (4.2, 1.3)
    rng = np.random.default_rng(0)
    readings = rssi_readings(tag, RECEIVERS, rng, beacons=1, power=power, exponent=2.0,
                             shadowing=0.0)
    assert math.dist(laterate(RECEIVERS, readings[0]), tag) < 0.05


def test_the_exponent_can_be_solved_with_five_receivers() -> None:
    receivers = np.vstack((RECEIVERS, [[3.0, 2.5]]))
    tag = (1.0, 3.8)
    readings = rssi_readings(tag, receivers, np.random.default_rng(1), beacons=1,
                             exponent=2.8, shadowing=0.0)
    assert math.dist(laterate(receivers, readings[0], exponent=None), tag) < 0.1


def test_smoothing_over_time_beats_one_beacon() -> None:
    rng = np.random.default_rng(2)
    one, smoothed = [], []
    for _ in range(40):
        tag = (rng.uniform(0.5, 5.5), rng.uniform(0.5, 4.5))
        readings = rssi_readings(tag, RECEIVERS, rng, beacons=30)
        localiser = TagLocaliser(RECEIVERS)
        assert localiser.estimate() is None
        localiser.add(readings[0])
        first = localiser.estimate()
        localiser.add(readings[1:])
        last = localiser.estimate()
        assert first is not None and last is not None
        one.append(math.dist(first, tag))
        smoothed.append(math.dist(last, tag))
    assert np.median(smoothed) < 0.6 * np.median(one)
    assert np.median(smoothed) < 0.8


def test_too_few_receivers_is_refused() -> None:
    with pytest.raises(ValueError, match="three receivers"):
        laterate(RECEIVERS[:2], np.array([-60.0, -70.0]))


def test_the_hint_puts_the_nearest_placement_first() -> None:
    placements = {"desk": ((1.0, 1.0), (1.0, 0.6)), "sofa": ((4.0, 3.0), (2.0, 0.9))}
    assert placement_hint((3.2, 2.9), placements) == ["sofa", "desk"]
    assert placement_hint((1.2, 0.4), placements)[0] == "desk"
