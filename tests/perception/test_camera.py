"""The head camera: ray-cast depth and colour, occlusion, noise growing with distance, edges."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.navigation import Navigator
from homebot.robot import HeadState, RgbdFrame
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.camera import CameraSimulator, SceneGeometry, Solid, camera_pose
from homebot.world import Shape, World

TABLE = np.array([[0.5, -0.6, 1.3, 0.6, 0.75]])  # x0, y0, x1, y1, top
HEAD = HeadState(0.0, 0.6)


def _render(solids: list[Solid], noise: bool = False, seed: int = 0) -> RgbdFrame:
    camera = CameraSimulator(SceneGeometry(np.zeros((0, 4)), TABLE),
                             np.random.default_rng(seed), noise=noise)
    return camera.render(0.0, (0.0, 0.0, 0.0), HEAD, solids)


def _pixel(frame: RgbdFrame, point: tuple[float, float, float]) -> tuple[int, int, float]:
    """The pixel (row, column) a base-frame point projects to, and its depth."""
    pose = frame.camera_pose
    optical = pose[:3, :3].T @ (np.asarray(point) - pose[:3, 3])
    k = frame.intrinsics
    return (round(k.fy * optical[1] / optical[2] + k.cy),
            round(k.fx * optical[0] / optical[2] + k.cx), float(optical[2]))


def test_an_object_stands_on_the_table_where_it_is() -> None:
    box = Solid(Shape.BOX, (0.1, 0.1, 0.2), (200, 30, 30), 0.9, 0.0, 0.75)
    frame = _render([box])
    assert frame.rgb.shape == (240, 320, 3) and frame.rgb.dtype == np.uint8
    assert frame.depth.shape == (240, 320) and frame.depth.dtype == np.float32
    row, column, depth = _pixel(frame, (0.9, 0.0, 0.95))  # the centre of its top face
    assert frame.depth[row, column] == pytest.approx(depth, abs=0.005)
    assert frame.rgb[row, column, 0] > 2 * frame.rgb[row, column, 1]  # red
    row, column, depth = _pixel(frame, (0.9, 0.4, 0.75))  # bare table beside it
    assert frame.depth[row, column] == pytest.approx(depth, abs=0.005)
    points, _ = frame.points()
    on_top = points[np.hypot(points[:, 0] - 0.9, points[:, 1]) < 0.03]
    assert on_top[:, 2].max() == pytest.approx(0.95, abs=0.005)


def test_a_nearer_object_hides_a_farther_one() -> None:
    back = Solid(Shape.CYLINDER, (0.08, 0.08, 0.15), (30, 30, 200), 1.1, 0.0, 0.75)
    front = Solid(Shape.BOX, (0.1, 0.3, 0.3), (30, 200, 30), 0.85, 0.0, 0.75)
    row, column, _ = _pixel(_render([back]), (1.1, 0.0, 0.85))
    alone, hidden = _render([back]), _render([back, front])
    assert alone.rgb[row, column, 2] > alone.rgb[row, column, 1]  # blue where it is alone
    assert hidden.rgb[row, column, 1] > hidden.rgb[row, column, 2]  # green in front of it
    assert hidden.depth[row, column] < alone.depth[row, column] - 0.1


def test_spheres_and_turned_boxes_render() -> None:
    ball = Solid(Shape.SPHERE, (0.1, 0.1, 0.1), (230, 210, 40), 0.9, 0.2, 0.75)
    turned = Solid(Shape.BOX, (0.04, 0.3, 0.1), (40, 70, 200), 0.9, -0.2, 0.75, yaw=math.pi / 2)
    points, _ = _render([ball, turned]).points()
    top_of_ball = points[np.hypot(points[:, 0] - 0.9, points[:, 1] - 0.2) < 0.01]
    assert top_of_ball[:, 2].max() == pytest.approx(0.85, abs=0.005)
    # turned by 90°, the box is long along x (0.3 m) and thin along y (0.04 m)
    box = points[(points[:, 2] > 0.8) & (np.abs(points[:, 1] + 0.2) < 0.2)]
    assert np.ptp(box[:, 0]) > 0.25 and np.ptp(box[:, 1]) < 0.06


def test_depth_noise_grows_with_distance_and_edges_lose_returns() -> None:
    box = Solid(Shape.BOX, (0.1, 0.1, 0.2), (200, 30, 30), 0.9, 0.0, 0.75)
    clean, noisy = _render([box]), _render([box], noise=True, seed=3)
    error = noisy.depth - clean.depth
    near, far = clean.depth < 1.0, clean.depth > 2.0
    assert np.nanstd(error[far]) > 2 * np.nanstd(error[near]) > 0
    row, column, _ = _pixel(clean, (0.9, 0.05, 0.95))  # the box's right edge, from the top
    window = noisy.depth[row - 15: row + 15, column - 6: column + 6]
    assert np.isnan(window).any()
    assert np.isnan(noisy.depth).mean() < 0.2 and not np.isnan(clean.depth[near]).any()


def test_camera_pose_looks_down_when_tilted() -> None:
    pose = camera_pose(HeadState(0.3, 0.5))
    forward = pose[:3, 2]
    assert forward[2] == pytest.approx(-math.sin(0.5))
    assert math.atan2(forward[1], forward[0]) == pytest.approx(0.3)
    assert np.allclose(pose[:3, :3] @ pose[:3, :3].T, np.eye(3))


SMALL = """\
name: kitchenette
rooms:
  - {name: kitchen, polygon: [[0, 0], [5, 0], [5, 4], [0, 4]]}
placements:
  - {name: table, category: table, room: kitchen, center: [2.5, 2.5], size: [1.2, 0.8],
     approach: [2.5, 1.73, 1.5708]}
objects:
  - {name: cola, category: drink, placement: table, position: [2.2, 2.4]}
  - {name: apple, category: fruit, placement: table, position: [2.6, 2.6]}
  - {name: cereal, category: food, placement: table, position: [2.85, 2.35]}
robot:
  pose: [2.5, 1.73, 1.5708]
"""


def test_sim_body_sees_the_objects_on_its_table() -> None:
    world = World.from_yaml_text(SMALL)
    simulation = Simulation(world, navigator=Navigator(world), seed=2)
    body = SimBody(simulation)
    body.point_head(0.0, 0.55)
    frame = body.camera()
    points, _ = frame.points()
    above = points[points[:, 2] > 0.77]
    x0, y0, theta = simulation.robot_pose
    c, s = math.cos(theta), math.sin(theta)
    for name in simulation.objects_on("table"):
        x, y = simulation.object_position[name]
        local = (c * (x - x0) + s * (y - y0), -s * (x - x0) + c * (y - y0))
        assert np.any(np.hypot(above[:, 0] - local[0], above[:, 1] - local[1]) < 0.03), name
    simulation.object_location["apple"] = "hand:left"  # picked up: no longer on the table
    points, _ = body.camera().points()
    x, y = simulation.object_position["apple"]
    local = (c * (x - x0) + s * (y - y0), -s * (x - x0) + c * (y - y0))
    above = points[points[:, 2] > 0.77]
    assert not np.any(np.hypot(above[:, 0] - local[0], above[:, 1] - local[1]) < 0.03)
