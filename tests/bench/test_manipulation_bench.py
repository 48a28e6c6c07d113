"""bench manipulation: bad input gives clear outcomes, and the figures come out as JSON."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("mujoco")

from homebot.cli import main


def test_bad_input_gives_outcomes_and_errors_never_a_traceback(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "manipulation", "--only", "bad-input", "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)["figures"]["bad input"]
    assert figures["unreachable target"] == "unreachable"
    assert figures["heavier than payload"] == "too_heavy"
    assert figures["malformed MJCF in a world file"].startswith("WorldError: $TMP/arm.xml:3:")


def test_grasping_figures_are_judged_by_the_truth(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "manipulation", "--only", "grasping", "--scenes", "2", "--json"]) == 0
    grasping = json.loads(capsys.readouterr().out)["figures"]["grasping"]
    assert grasping["scenes"] == 2
    assert 0.0 <= grasping["verified picks %"] <= 100.0
    assert sum(grasping["outcomes"].values()) == 2
    assert main(["bench", "manipulation", "--scenes", "0"]) == 2


def test_grasps_are_planned_on_the_clusters_the_camera_sees() -> None:
    import math

    import numpy as np

    from homebot.bench.manipulation import generate_scene, perceive, run_pick

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
