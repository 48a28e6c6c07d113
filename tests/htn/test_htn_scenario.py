"""``homebot scenario jenny``: the Care-O-bot paper's two scenarios, planned and monitored."""

from __future__ import annotations

import json

import pytest

from homebot.cli import main


def test_jenny_scenario_with_a_retried_grasp(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "jenny", "--seed", "2", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["scenario"] == "jenny" and summary["success"] is True
    assert summary["table1"] == {"bring_object": {"plans": 3, "shortest": 8},
                                 "guide_person": {"plans": 1, "shortest": 5}}
    grasp = next(a for a in summary["actions"] if a["operator"] == "!grasp")
    assert (grasp["status"], grasp["attempts"]) == ("verified", 3)
    assert summary["statuses"]["retrying"] == 2 and summary["statuses"]["aborted"] == 2
    assert summary["speech"][-1] == "Alex, we have arrived at the bedroom."


def test_jenny_scenario_prints_for_people(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["scenario", "jenny", "--door-closed", "1", "--slip", "0"]) == 0
    out = capsys.readouterr().out
    assert "Table 1, bring_object: 3 solution plans, shortest 8" in out
    assert "verified  (!guide robot Alex bedroom)" in out
