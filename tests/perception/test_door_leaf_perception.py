"""The door leaf, handle and hinge perceived from depth points (perception/door_leaf.py)."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.perception.door_leaf import perceive_door


def _grid(y: tuple[float, float], z: tuple[float, float], x: float,
          spacing: float = 0.02) -> np.ndarray:
    ys, zs = np.meshgrid(np.arange(y[0], y[1], spacing), np.arange(z[0], z[1], spacing))
    return np.column_stack((np.full(ys.size, x), ys.ravel(), zs.ravel()))


def _doorway(rng: np.random.Generator, handle_y: float | None, *, yaw: float = 0.0,
             leaf: tuple[float, float] = (-0.4, 0.4)) -> np.ndarray:
    """A wall 1.2 m ahead with a shut leaf set 4 cm back between jamb gaps, and a handle."""
    parts = [_grid((-1.5, leaf[0] - 0.05), (0.0, 2.2), 1.2),   # wall right of the door
             _grid((leaf[1] + 0.05, 1.5), (0.0, 2.2), 1.2),    # wall left of it
             _grid(leaf, (0.0, 2.0), 1.24)]                    # the leaf
    if handle_y is not None:
        handle = _grid((handle_y - 0.06, handle_y + 0.06), (1.03, 1.07), 1.18, 0.01)
        parts.append(handle)
        # the handle hides the leaf behind it
        parts[2] = parts[2][~((np.abs(parts[2][:, 1] - handle_y) < 0.06)
                              & (np.abs(parts[2][:, 2] - 1.05) < 0.02))]
    points = np.vstack(parts)
    points = points + rng.normal(0.0, 0.003, points.shape)
    turn = np.array([[np.cos(yaw), -np.sin(yaw), 0.0], [np.sin(yaw), np.cos(yaw), 0.0],
                     [0.0, 0.0, 1.0]])
    turned: np.ndarray = points @ turn.T
    return turned


@pytest.mark.parametrize("yaw", [0.0, 0.35, -0.3])
def test_the_hinge_is_the_edge_away_from_the_handle(yaw: float) -> None:
    points = _doorway(np.random.default_rng(3), handle_y=0.32, yaw=yaw)
    seen = perceive_door(points, np.random.default_rng(0))
    assert seen is not None
    turn = np.array([[np.cos(yaw), -np.sin(yaw)], [np.sin(yaw), np.cos(yaw)]])
    assert np.linalg.norm(seen.hinge - turn @ [1.24, -0.4]) < 0.04
    assert np.linalg.norm(seen.latch - turn @ [1.24, 0.4]) < 0.04
    assert np.linalg.norm(seen.handle[:2] - turn @ [1.18, 0.32]) < 0.03
    assert abs(seen.handle[2] - 1.05) < 0.03
    assert seen.width == pytest.approx(0.8, abs=0.06)
    assert float(seen.normal @ (turn @ [-1.0, 0.0])) > 0.99  # towards the robot


def test_a_handle_on_the_other_side_swaps_the_hinge() -> None:
    seen = perceive_door(_doorway(np.random.default_rng(4), handle_y=-0.32),
                         np.random.default_rng(0))
    assert seen is not None
    assert seen.hinge[1] > 0.3 and seen.latch[1] < -0.3


def test_no_handle_is_no_door_to_open() -> None:
    assert perceive_door(_doorway(np.random.default_rng(5), handle_y=None),
                         np.random.default_rng(0)) is None


def test_a_knob_mid_leaf_is_no_handle() -> None:
    assert perceive_door(_doorway(np.random.default_rng(6), handle_y=0.0),
                         np.random.default_rng(0)) is None


def test_a_bare_wall_is_no_door() -> None:
    wall = _grid((-1.5, 1.5), (0.0, 2.2), 1.2)
    assert perceive_door(wall, np.random.default_rng(0)) is None
