"""bench manipulation: the figures come out as JSON, judged by the truth."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("mujoco")

from homebot.cli import main


def test_grasping_figures_are_judged_by_the_truth(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "manipulation", "--only", "grasping", "--scenes", "2", "--json"]) == 0
    grasping = json.loads(capsys.readouterr().out)["figures"]["grasping"]
    assert grasping["scenes"] == 2
    assert 0.0 <= grasping["verified picks %"] <= 100.0
    assert sum(grasping["outcomes"].values()) == 2
    assert main(["bench", "manipulation", "--scenes", "0"]) == 2
