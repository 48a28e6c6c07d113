"""The $1 recogniser on hand strokes: shapes named, directions apart, stillness no gesture."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.perception.strokes import POINTS, StrokeRecogniser, frontal_stroke, normalise


@pytest.fixture(scope="module")
def recogniser() -> StrokeRecogniser:
    return StrokeRecogniser()


def _noisy(points: np.ndarray, seed: int) -> np.ndarray:
    noisy: np.ndarray = points + np.random.default_rng(seed).normal(0.0, 0.01, points.shape)
    return noisy


def test_a_stroke_is_resampled_scaled_and_centred() -> None:
    points = normalise(np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.25]]))
    assert points is not None and points.shape == (POINTS, 2)
    assert np.allclose(points.mean(axis=0), 0.0)
    assert float(np.ptp(points, axis=0).max()) == pytest.approx(1.0)
    assert normalise(np.zeros((5, 2))) is None


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_shapes_drawn_by_hand_are_named(recogniser: StrokeRecogniser, seed: int) -> None:
    t = np.linspace(0.0, 1.0, 20)
    circle = np.column_stack((0.18 * np.cos(2.2 * math.pi * t + seed),
                              0.18 * np.sin(2.2 * math.pi * t + seed)))
    right = np.column_stack((np.linspace(-0.25, 0.45, 12), np.zeros(12)))
    beckon = np.column_stack((0.02 * np.sin(6 * math.pi * t), 0.15 * np.sin(6 * math.pi * t)))
    wave = np.column_stack((0.15 * np.sin(8 * math.pi * t), 0.02 * np.sin(8 * math.pi * t)))
    assert recogniser.recognise(_noisy(circle, seed))[0] == "circle"
    assert recogniser.recognise(_noisy(right, seed))[0] == "swipe_right"
    assert recogniser.recognise(_noisy(right[::-1], seed))[0] == "swipe_left"
    assert recogniser.recognise(_noisy(beckon, seed))[0] == "beckon"
    assert recogniser.recognise(_noisy(wave, seed))[0] == "wave"


def test_a_hand_held_still_draws_nothing(recogniser: StrokeRecogniser) -> None:
    assert recogniser.recognise(_noisy(np.zeros((20, 2)), 4)) == (None, 0.0)


def test_the_stroke_is_seen_from_the_persons_front() -> None:
    # the person at the origin faces the robot on +x: their right is -y
    hands = np.array([[0.3, 0.2, 1.4], [0.3, -0.2, 1.5]])
    stroke = frontal_stroke(hands, np.array([0.0, 0.0, 1.6]), (2.0, 0.0))
    assert np.allclose(stroke, [[-0.2, 1.4], [0.2, 1.5]])
