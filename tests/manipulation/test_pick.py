"""Picks in physics: the object is held only if the simulator keeps it in the fingers."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("mujoco")

from homebot.manipulation.control import free_spots
from homebot.sim.arm import ObjectBody, SurfaceBox
from homebot.trials.picking import Scene, generate_scene, run_pick

TABLE = SurfaceBox("table", (0.65, 0.0), (0.5, 0.8), 0.75)


def test_a_box_is_picked_and_held_by_the_truth_and_the_monitor_agrees() -> None:
    box = ObjectBody("box", "box", (0.06, 0.12, 0.15), 0.3, position=(0.6, 0.05), base=0.75,
                     yaw=0.5)
    cup = ObjectBody("cup", "cylinder", (0.07, 0.07, 0.1), 0.25, position=(0.62, -0.2),
                     base=0.75)
    result = run_pick(Scene(TABLE, [box, cup], "box"), np.random.default_rng(0))
    assert result["held"] and result["outcome"] == "held"
    assert result["simulated"] > 1.0  # it took simulated time to move


def test_an_object_too_heavy_is_refused_and_one_too_far_is_unreachable() -> None:
    rng = np.random.default_rng(0)
    anvil = ObjectBody("anvil", "box", (0.06, 0.06, 0.08), 5.0, position=(0.6, 0.0))
    assert run_pick(Scene(TABLE, [anvil], "anvil"), rng)["outcome"] == "too_heavy"
    long_table = SurfaceBox("table", (1.3, 0.0), (1.8, 0.8), 0.75)
    far = ObjectBody("far", "sphere", (0.07, 0.07, 0.07), 0.2, position=(2.0, 0.0))
    outcome = run_pick(Scene(long_table, [far], "far"), rng)
    assert outcome["outcome"] == "unreachable" and not outcome["held"]


def test_a_heavy_object_slips_when_the_grip_is_too_weak() -> None:
    # above what two fingers squeezing 20 N with friction 0.3 can hold (~1.2 kg), below the
    # payload check (that one is told a light mass): physics decides, not a die
    slippery = ObjectBody("brick", "box", (0.06, 0.06, 0.16), 1.45, friction=0.3,
                          position=(0.6, 0.0))
    result = run_pick(Scene(TABLE, [slippery], "brick"), np.random.default_rng(0))
    assert not result["held"]
    assert result["outcome"] == "not_held"  # the robot's senses notice the empty hand
    grippy = ObjectBody("brick", "box", (0.06, 0.06, 0.16), 1.45, friction=0.8,
                        position=(0.6, 0.0))
    assert run_pick(Scene(TABLE, [grippy], "brick"), np.random.default_rng(0))["held"]


def test_generated_scenes_hold_one_to_six_catalogue_objects_apart() -> None:
    shapes = set()
    for seed in range(12):
        scene = generate_scene(np.random.default_rng(seed))
        assert 1 <= len(scene.objects) <= 6
        shapes |= {o.shape for o in scene.objects}
        assert scene.target in {o.name for o in scene.objects}
    assert shapes == {"box", "cylinder", "sphere"}


def test_free_spots_keep_clear_of_the_objects_already_there() -> None:
    spots = free_spots((0.0, 0.0), (0.6, 0.6), [(0.0, 0.0, 0.1)], 0.05, (0.3, 0.0))
    assert spots
    assert all(np.hypot(*spot) >= 0.18 for spot in spots)
    assert spots[0][0] > 0.1  # the one nearest where the robot wants it comes first
    assert free_spots((0.0, 0.0), (0.1, 0.1), [], 0.08, (0.0, 0.0)) == []
