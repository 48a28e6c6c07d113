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
