"""The carried table's pitch and the plant pot's rim, from laser ranges alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.perception.plant_pot import PotScan, fit_circle
from homebot.perception.table_pitch import TablePitch

HAND = np.array([0.72, 0.0, 0.76])


def _ranges_to_table(tracker: TablePitch, pitch: float, torso: float, yaw: float,
                     rng: np.random.Generator) -> np.ndarray:
    """Ranges along the tracker's fan to a table top rising at ``pitch`` from just below
    the hand for 1.24 m, then the floor; 1 cm of range noise."""
    rotation = np.array([[math.cos(yaw), -math.sin(yaw), 0.0],
                         [math.sin(yaw), math.cos(yaw), 0.0], [0.0, 0.0, 1.0]])
    rays = tracker.directions(rotation)
    mount = tracker.mount(torso)
    heading = np.array([math.cos(yaw), math.sin(yaw)])
    top = HAND[2] - 0.03
    ranges = np.full(len(rays), np.inf)
    for k, ray in enumerate(rays):
        # mount + t·ray meets the top's line: z = top + tan(pitch)·run
        along = float(ray[:2] @ heading)
        start = float((mount[:2] - HAND[:2]) @ heading)
        across = float(ray[2]) - math.tan(pitch) * along
        t = (top + math.tan(pitch) * start - mount[2]) / across if abs(across) > 1e-9 else -1
        run = start + t * along
        if t > 0 and 0.0 < run < 1.24 * math.cos(pitch):
            ranges[k] = t
        elif ray[2] < 0:
            ranges[k] = -mount[2] / ray[2]  # the floor
    return ranges + rng.normal(0.0, 0.01, len(ranges))


@pytest.mark.parametrize("pitch_deg", [-6.0, -1.0, 0.0, 2.0, 8.0])
def test_the_table_pitch_is_the_slope_of_its_top(pitch_deg: float) -> None:
    rng = np.random.default_rng(3)
    tracker = TablePitch()
    for yaw in (0.0, 0.3):
        ranges = _ranges_to_table(tracker, math.radians(pitch_deg), 0.2, yaw, rng)
        rotation = np.array([[math.cos(yaw), -math.sin(yaw), 0.0],
                             [math.sin(yaw), math.cos(yaw), 0.0], [0.0, 0.0, 1.0]])
        pitch = tracker.update(0.2, HAND, rotation, ranges)
        assert math.degrees(pitch) == pytest.approx(pitch_deg, abs=0.3)
        assert tracker.points >= 20


def test_the_table_pitch_holds_when_the_scan_shows_no_top() -> None:
    tracker = TablePitch()
    tracker.pitch = 0.05
    nothing = np.full(len(tracker.angles), np.inf)
    assert tracker.update(0.0, HAND, np.eye(3), nothing) == 0.05


def test_a_circle_is_fitted_to_an_arc() -> None:
    rng = np.random.default_rng(4)
    angles = rng.uniform(math.pi * 0.8, math.pi * 1.3, 60)
    arc = np.column_stack((0.7 + 0.1 * np.cos(angles), 0.2 + 0.1 * np.sin(angles)))
    centre, radius = fit_circle(arc + rng.normal(0.0, 0.003, arc.shape))
    assert np.allclose(centre, [0.7, 0.2], atol=0.01) and radius == pytest.approx(0.1, abs=0.01)


def test_no_pot_in_an_empty_sweep() -> None:
    sweep = PotScan()
    assert sweep.find(0.0, np.full(len(sweep.azimuth), np.inf)) is None
