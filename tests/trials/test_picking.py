"""Picking trials: bad input gives a clear outcome or an error; grasps on what is seen."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("mujoco")

from homebot.errors import WorldError
from homebot.sim.arm import ArmSimulation, ObjectBody, SurfaceBox
from homebot.trials.picking import Scene, generate_scene, perceive, run_pick


def test_an_unreachable_object_and_one_above_the_payload_give_clear_outcomes() -> None:
    rng = np.random.default_rng(7)
    table = SurfaceBox("table", (1.4, 0.0), (1.6, 0.8), 0.75)
    far = ObjectBody("far cup", "cylinder", (0.07, 0.07, 0.12), 0.3, position=(2.0, 0.0))
    heavy = ObjectBody("anvil", "box", (0.08, 0.08, 0.1), 6.0, position=(0.75, 0.0))
    near = SurfaceBox("table", (0.65, 0.0), (0.5, 0.8), 0.75)
    assert run_pick(Scene(table, [far], far.name), rng)["outcome"] == "unreachable"
    assert run_pick(Scene(near, [heavy], heavy.name), rng)["outcome"] == "too_heavy"


def test_a_malformed_arm_model_is_an_error_naming_file_and_line(tmp_path: Path) -> None:
    broken = tmp_path / "arm.xml"
    broken.write_text("<mujoco>\n  <worldbody>\n    <body><geom size='x'/></body>\n"
                      "  </worldbody>\n</mujoco>\n", encoding="utf-8")
    with pytest.raises(WorldError) as raised:
        ArmSimulation(base=(0.0, 0.0, 0.0), model_path=broken)
    assert str(raised.value).startswith(f"{broken}:3:")


def test_grasps_are_planned_on_the_clusters_the_camera_sees() -> None:
    rng = np.random.default_rng(3)
    scene = generate_scene(rng)  # one box, 9.8 x 23.5 x 8.8 cm, turned 84 degrees
    target = next(o for o in scene.objects if o.name == scene.target)
    seen = perceive(scene, np.random.default_rng([3, 1802]))
    assert seen.target is not None and not seen.unseen
    assert math.dist(seen.target.center, target.position) < 0.02
    assert seen.target.height == pytest.approx(target.extents[2], abs=0.01)
    assert seen.target.extents[0] == pytest.approx(max(target.extents[:2]), abs=0.02)
    along = math.atan2(seen.target.axes[0][1], seen.target.axes[0][0])
    long_side = target.yaw + (math.pi / 2 if target.extents[1] > target.extents[0] else 0.0)
    assert abs(math.sin(along - long_side)) < math.sin(math.radians(10))
    picked = run_pick(scene, rng, perceived=True, seed=3)
    assert picked["target_seen"] and picked["held"] and picked["outcome"] == "held"
