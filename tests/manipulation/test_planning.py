"""IK, RRT-Connect and grasp candidates on the arm's own planning scene."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("mujoco")

from homebot.manipulation.grasps import ObjectGeometry, grasp_candidates, select_grasp
from homebot.manipulation.ik import solve_ik
from homebot.manipulation.pick import TUCKED, plan_motion
from homebot.manipulation.rrt import edge_valid, rrt_connect, shortcut
from homebot.manipulation.scene import Obstacle, PlanningScene
from homebot.sim.arm import default_arm_model

TABLE = Obstacle("table", "box", (0.5, 0.8, 0.75), (0.65, 0.0, 0.375))


def _scene(*extra: Obstacle) -> PlanningScene:
    return PlanningScene(default_arm_model(), (0.0, 0.0, 0.0), [TABLE, *extra])


def test_ik_reaches_a_pose_the_arm_can_take_and_refuses_one_out_of_reach() -> None:
    scene = _scene()
    goal = np.array([0.3, 0.2, 0.1, 0.3, 1.2, -0.2, 0.5, 0.4])
    position, rotation = scene.grasp_frame(goal)
    found = solve_ik(scene, position, rotation, [TUCKED, goal * 0.5], iterations=200)
    assert found is not None
    reached, turned = scene.grasp_frame(found)
    assert np.linalg.norm(reached - position) < 0.005
    assert np.allclose(turned, rotation, atol=0.05)
    assert solve_ik(scene, np.array([3.0, 0.0, 1.0]), rotation, [TUCKED]) is None


def test_rrt_connect_finds_a_free_path_round_a_wall_and_shortcut_keeps_it_free() -> None:
    def valid(q: np.ndarray) -> bool:  # a wall at x = 0 with a gap above y = 0.6
        return not (abs(q[0]) < 0.1 and q[1] < 0.6)

    rng = np.random.default_rng(3)
    start, goal = np.array([-0.8, -0.5]), np.array([0.8, -0.5])
    path = rrt_connect(start, goal, valid, np.array([-1.0, -1.0]), np.array([1.0, 1.0]), rng)
    assert path is not None
    assert np.allclose(path[0], start) and np.allclose(path[-1], goal)
    smooth = shortcut(path, valid, rng)
    for a, b in itertools.pairwise(smooth):
        assert valid(a) and edge_valid(valid, a, b)
    assert len(smooth) <= len(path)
    assert not edge_valid(valid, start, goal)


def test_the_arm_plans_round_the_table_and_collisions_are_seen() -> None:
    scene = _scene()
    inside = np.array([0.0, 0.0, 0.9, 0.0, 0.3, 0.0, 0.3, 0.0])  # hand down into the table
    assert scene.collides(inside)
    assert not scene.collides(TUCKED)
    path = plan_motion(scene, TUCKED, np.array([0.3, 0.0, -0.3, 0.0, 1.3, 0.0, 0.6, 0.0]),
                       np.random.default_rng(0))
    assert path is not None
    assert all(not scene.collides(q) for q in path)


def test_grasps_follow_the_objects_proportions() -> None:
    tall = ObjectGeometry.from_shape("bottle", "cylinder", (0.07, 0.07, 0.25), (0.6, 0.0),
                                     0.0, 0.75)
    flat = ObjectGeometry.from_shape("box", "box", (0.06, 0.15, 0.05), (0.6, 0.0), 0.4, 0.75)
    robot = np.zeros(2)
    assert grasp_candidates(tall, robot)[0].kind == "side"
    best = grasp_candidates(flat, robot)[0]
    assert best.kind == "top"
    assert best.width == pytest.approx(0.06)  # closing across the narrow side
    closing = best.rotation[:2, 1]
    assert abs(closing @ np.array([math.cos(0.4), math.sin(0.4)])) > 0.99
    too_wide = ObjectGeometry.from_shape("tray", "box", (0.4, 0.5, 0.03), (0.6, 0.0), 0.0,
                                         0.75)
    assert grasp_candidates(too_wide, robot) == []


def test_principal_axes_come_from_a_cluster() -> None:
    rng = np.random.default_rng(1)
    local = rng.uniform([-0.1, -0.03, 0.0], [0.1, 0.03, 0.12], size=(400, 3))
    yaw = 0.7
    turn = np.array([[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0],
                     [0, 0, 1]])
    points = local @ turn.T + np.array([0.6, 0.1, 0.75])
    geometry = ObjectGeometry.from_points("box", points, 0.75)
    assert abs(geometry.axes[0] @ np.array([math.cos(yaw), math.sin(yaw)])) > 0.99
    assert geometry.extents[0] == pytest.approx(0.2, abs=0.02)
    assert geometry.extents[1] == pytest.approx(0.06, abs=0.01)
    assert geometry.height == pytest.approx(0.12, abs=0.01)
    assert np.allclose(geometry.center, (0.6, 0.1), atol=0.01)


def test_a_grasp_is_selected_only_where_the_arm_reaches_without_collision() -> None:
    can = Obstacle("can", "cylinder", (0.07, 0.07, 0.12), (0.6, 0.0, 0.81))
    scene = _scene(can)
    near = ObjectGeometry.from_shape("can", "cylinder", (0.07, 0.07, 0.12), (0.6, 0.0), 0.0,
                                     0.75)
    grasp = select_grasp(scene, near, TUCKED)
    assert grasp is not None
    assert not scene.collides(grasp.pre_grasp, gripper=grasp.candidate.opening())
    position, _ = scene.grasp_frame(grasp.grasp)
    assert np.linalg.norm(position - grasp.candidate.position) < 0.01
    far = ObjectGeometry.from_shape("far", "cylinder", (0.07, 0.07, 0.12), (1.6, 0.0), 0.0,
                                    0.75)
    assert select_grasp(_scene(), far, TUCKED) is None


def test_a_round_objects_top_grasps_close_across_then_along_the_line_of_sight() -> None:
    # seen diagonally from the robot, whatever heading the map gives the plate
    plate = ObjectGeometry.from_shape("plate", "cylinder", (0.16, 0.16, 0.05), (0.5, 0.5),
                                      0.3, 0.75)
    sight = np.array([1.0, 1.0]) / math.sqrt(2)
    tops = [c for c in grasp_candidates(plate, np.zeros(2)) if c.kind == "top"]
    axes: list[np.ndarray] = []
    for candidate in tops:  # each closing line once, in rank order
        if all(abs(candidate.rotation[:2, 1] @ seen) < 0.99 for seen in axes):
            axes.append(candidate.rotation[:2, 1])
    assert len(axes) == 4
    assert abs(axes[0] @ sight) < 0.01  # across the view first
    assert abs(axes[1] @ sight) > 0.99  # then along it
    # the two wrist rolls of one closing line are one grasp; another line is another
    first, same, other = tops[0], next(c for c in tops[1:] if abs(
        c.rotation[:2, 1] @ axes[0]) > 0.99), next(c for c in tops if abs(
            c.rotation[:2, 1] @ axes[1]) > 0.99)
    assert first.resembles(same) and not first.resembles(other)
    moved = plate.center + np.array([0.05, 0.0])
    assert not first.resembles(replace(first, position=np.array([*moved, first.position[2]])))


def test_grasps_like_failed_ones_are_not_selected() -> None:
    can = Obstacle("can", "cylinder", (0.07, 0.07, 0.12), (0.6, 0.0, 0.81))
    scene = _scene(can)
    geometry = ObjectGeometry.from_shape("can", "cylinder", (0.07, 0.07, 0.12), (0.6, 0.0),
                                         0.0, 0.75)
    first = select_grasp(scene, geometry, TUCKED)
    assert first is not None
    second = select_grasp(scene, geometry, TUCKED, avoid=[first.candidate])
    assert second is not None and not second.candidate.resembles(first.candidate)
    everything = grasp_candidates(geometry, np.zeros(2))
    assert select_grasp(scene, geometry, TUCKED, avoid=everything) is None


def test_a_flat_object_gets_no_side_grasp_that_would_hold_only_its_top_edge() -> None:
    # A side grasp's fingers cannot go lower than 4.7 cm beside an object (the hand would
    # meet the table): a 5 cm cup would hang from its top edge and tip out once the hand
    # turned to hold it out. A can of 12 cm is still taken from the side.
    robot = np.zeros(2)
    cup = ObjectGeometry.from_shape("cup", "cylinder", (0.156, 0.156, 0.049), (0.5, 0.0),
                                    0.0, 0.75)
    assert {c.kind for c in grasp_candidates(cup, robot)} == {"top"}
    gadget = ObjectGeometry.from_shape("gadget", "box", (0.08, 0.15, 0.04), (0.5, 0.0), 0.0,
                                       0.75)
    assert {c.kind for c in grasp_candidates(gadget, robot)} == {"top"}
    can = ObjectGeometry.from_shape("can", "cylinder", (0.07, 0.07, 0.12), (0.5, 0.0), 0.0,
                                    0.75)
    assert "side" in {c.kind for c in grasp_candidates(can, robot)}
