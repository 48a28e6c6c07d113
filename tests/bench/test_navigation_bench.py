"""bench navigation: one goal driven alone in its situation, the same as in the whole run."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

pytest.importorskip("cv2")

from homebot.cli import main

_DRIVE = ["bench", "navigation", "--repeat", "1", "--goals", "2", "--planner", "stage2",
          "--walkers", "2", "--seed", "3", "--json"]


def _stage2(capsys: pytest.CaptureFixture[str]) -> dict[str, object]:
    figures: dict[str, object] = json.loads(capsys.readouterr().out)["figures"]["driving"][
        "stage2"]
    return figures


def test_one_goal_alone_from_its_snapshot_drives_as_in_the_whole_run(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    snapshots, trace = tmp_path / "snapshots", tmp_path / "trace.jsonl"
    assert main([*_DRIVE, "--snapshots", str(snapshots)]) == 0
    whole = _stage2(capsys)["per goal"]
    assert sorted(p.name for p in snapshots.iterdir()) == [
        "goal-0000-stage2.pickle.gz", "goal-0001-stage2.pickle.gz"]
    assert main([*_DRIVE, "--snapshots", str(snapshots), "--only-goal", "1",
                 "--trace", str(trace)]) == 0
    alone = _stage2(capsys)
    assert alone["goals"] == 1
    assert alone["per goal"] == {"first": 1, "reached": whole["reached"][1:],  # type: ignore
                                 "seconds": whole["seconds"][1:]}  # type: ignore[index]
    record = json.loads(trace.read_text())
    assert record["goal"] == 1 and record["duration"] == whole["seconds"][1]  # type: ignore
    assert record["ticks"] and record["plans"]
    assert set(record["ticks"][0]["people"]) >= {"Alex", "John"}


def test_bad_goal_choices_and_foreign_snapshots_are_refused_in_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([*_DRIVE, "--only-goal", "2"]) == 2
    assert "--only-goal 2: there are only 2 goals" in capsys.readouterr().err
    snapshots = tmp_path / "snapshots"
    snapshots.mkdir()
    (snapshots / "goal-0001-stage2.pickle.gz").write_bytes(b"not a snapshot")
    assert main([*_DRIVE, "--snapshots", str(snapshots), "--from", "1"]) == 2
    assert "was kept by other code" in capsys.readouterr().err
