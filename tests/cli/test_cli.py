"""The command line, in-process: exit codes, JSON output, clear errors without tracebacks."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main
from homebot.cli.world import last_run_path

TASK = """\
description: bring the cola
steps:
  - {skill: navigate, to: fridge}
  - {skill: find_object, object: cola, placement: fridge}
  - {skill: pick, object: cola}
  - {skill: navigate, to: operator}
  - {skill: give, person: operator}
"""


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_run_task_json(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["run-task", str(_file(tmp_path, "task.yaml", TASK)), "--json"])
    report = json.loads(capsys.readouterr().out)
    assert status == 0
    assert report["success"] is True
    assert [step["status"] for step in report["steps"]] == ["verified"] * 5
    assert set(report) == {"success", "steps", "speech", "sim_time", "reason"}
    assert report["steps"][0] == {"skill": "navigate", "args": {"to": "fridge"},
                                  "status": "verified", "error": None}


def test_failed_task_exits_1(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    task = _file(tmp_path, "task.yaml", "- {skill: give, person: operator}\n")
    assert main(["run-task", str(task), "--json"]) == 1


@pytest.mark.parametrize(("task", "expected"), [
    ("- {skill: place, placement: window}\n", "unknown placement 'window'"),
    ("- {skill: pick}\n", "needs argument 'object'"),
    ("- {skill: fly, to: moon}\n", "unknown skill 'fly'"),
    ("steps: [\n", "YAML syntax error"),
])
def test_bad_tasks_exit_2_with_a_clear_message(tmp_path: Path, task: str, expected: str,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["run-task", str(_file(tmp_path, "task.yaml", task))])
    captured = capsys.readouterr()
    assert status == 2
    assert expected in captured.err
    assert "Traceback" not in captured.err + captured.out


def test_world_with_a_typo_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    source = Path(__file__).resolve().parents[2] / "src/homebot/data/worlds/supermarket.yaml"
    broken = source.read_text().replace("holds: [drink]", "hodls: [drink]")
    status = main(["world", "check", str(_file(tmp_path, "w.yaml", broken))])
    err = capsys.readouterr().err
    assert status == 2 and "hodls" in err and "did you mean 'holds'" in err and "line" in err


def test_world_with_a_door_to_nowhere_exits_2(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    source = Path(__file__).resolve().parents[2] / "src/homebot/data/worlds/supermarket.yaml"
    broken = source.read_text().replace("rooms: [shop floor, storage]",
                                        "rooms: [shop floor, cellar]")
    assert main(["world", "check", str(_file(tmp_path, "w.yaml", broken))]) == 2
    assert "unknown room 'cellar'" in capsys.readouterr().err


def test_world_check_ok(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["world", "check", "apartment"]) == 0
    assert "ok" in capsys.readouterr().out


def test_world_show_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["world", "show", "--world", "supermarket", "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert {"rooms", "doors", "placements", "objects", "people"} <= set(shown)
    assert {"name": "coke", "category": "drink", "placement": "shelf drinks"} in shown["objects"]


def test_world_show_png_draws_the_last_path(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    events = tmp_path / "events.jsonl"
    assert main(["run-task", str(_file(tmp_path, "task.yaml", TASK)), "--json",
                 "--events", str(events)]) == 0
    png = tmp_path / "map.png"
    assert main(["world", "show", "--png", str(png), "--events", str(events)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert any('"robot.path"' in line for line in events.read_text().splitlines())


def test_demo_runs_and_ends_with_a_table(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "outcomes and simulated durations" in out
    assert last_run_path().exists()


def test_world_show_draws_the_last_run_by_default(tmp_path: Path,
                                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run-task", str(_file(tmp_path, "task.yaml", TASK)), "--json"]) == 0
    assert '"robot.path"' in last_run_path().read_text()
    png = tmp_path / "map.png"
    assert main(["world", "show", "--png", str(png)]) == 0
    assert png.exists()


def test_bench_robustness_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "robustness", "--tasks", "5", "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    assert [mode["tasks"] for mode in figures["modes"]] == [5, 5]


def test_no_command_prints_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([]) == 2


def test_do_understands_and_carries_out_a_command(capsys: pytest.CaptureFixture[str]) -> None:
    command = "find a fruit in the kitchen then get it and deliver it to Maria in the kitchen"
    assert main(["do", command, "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["success"] is True
    assert [step["skill"] for step in report["steps"]] == [
        "navigate", "find_object", "pick", "navigate", "find_person", "give"]
    assert report["steps"][2]["args"]["object"] in {"apple", "banana", "orange", "lemon", "pear"}


@pytest.mark.parametrize(("start", "command", "said"), [
    ("2026-11-29 14:30", "tell me what day is today", "Today is Sunday."),
    ("2026-11-29 14:30", "tell me what day is tomorrow", "Tomorrow is Monday."),
    ("2026-11-22 08:00", "tell me the day of the month", "Today is the 22nd of November."),
    ("2026-03-01 16:05", "tell me the time", "It is 16:05."),
])
def test_the_clock_starts_at_the_date_and_time_given(start: str, command: str, said: str,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["do", command, "--start", start, "--json"]) == 0
    assert said in json.loads(capsys.readouterr().out)["speech"][0]


def test_do_refuses_the_impossible_with_a_reason(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["do", "fetch the kitchen", "--json"]) == 1
    said = json.loads(capsys.readouterr().out)["speech"][0]
    assert "kitchen" in said and "room" in said


def test_scenario_json_summary(capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["scenario", "fetch", "--seed", "3", "--json"])
    summary = json.loads(capsys.readouterr().out)
    assert {"scenario", "success", "actions", "speech"} <= set(summary)
    assert summary["scenario"] == "fetch"
    assert status == (0 if summary["success"] else 1)


def test_unknown_scenario_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["scenario", "moonwalk"])
    assert exit_info.value.code == 2


def test_retry_budgets_from_the_command_line(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    task = _file(tmp_path, "task.yaml", TASK)
    assert main(["run-task", str(task), "--json", "--retries", "pick=0,navigate=2"]) == 0
    capsys.readouterr()
    assert main(["run-task", str(task), "--retries", "pick=many"]) == 2
    assert "needs a count" in capsys.readouterr().err
    assert main(["do", "bring me the cola from the fridge", "--retries", "grab=1"]) == 2
    assert "unknown skill 'grab'" in capsys.readouterr().err
