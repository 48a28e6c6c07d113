"""``homebot bench sweep``: a tiny symbolic grid on two workers, the same table as on one,
resumed after a stop without redoing what was finished, and bad specs refused in one line."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

import pytest

from homebot.bench.sweep import COLUMNS, RUN_COLUMNS, TABLE
from homebot.cli import main

SPEC = """\
worlds: [apartment]
levels: [0, 2]
seeds: [3]
tasks: 2
"""


def _sweep(capsys: pytest.CaptureFixture[str], spec: Path, out: Path,
           workers: int) -> dict[str, Any]:
    assert main(["bench", "sweep", str(spec), "--out", str(out), "--workers", str(workers),
                 "--json"]) == 0
    figures: dict[str, Any] = json.loads(capsys.readouterr().out)
    return figures


def _results(out: Path) -> list[dict[str, str]]:
    """The table's rows without what differs from run to run (worker, wall time)."""
    with (out / TABLE).open(newline="", encoding="utf-8") as handle:
        return [{column: value for column, value in row.items() if column not in RUN_COLUMNS}
                for row in csv.DictReader(handle)]


@pytest.fixture
def spec(tmp_path: Path) -> Path:
    path = tmp_path / "grid.yaml"
    path.write_text(SPEC, encoding="utf-8")
    return path


def test_two_workers_write_the_table_one_worker_writes(
        spec: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    two = _sweep(capsys, spec, tmp_path / "two", 2)
    one = _sweep(capsys, spec, tmp_path / "one", 1)
    assert (two["tasks"], two["ran"], two["kept"], two["errors"]) == (8, 8, 0, 0)
    rows = _results(tmp_path / "two")
    assert rows == _results(tmp_path / "one")
    assert [(row["level"], row["mode"], row["index"]) for row in rows] == [
        (level, mode, index) for level in ("0", "2")
        for mode in ("monitored + recovery", "plain sequence") for index in ("0", "1")]
    assert {row["run_seed"] for row in rows} == {"300009", "300010"}  # seed and index alone
    assert all(row["verified"] in {"True", "False"} and row["attempts"] == "1" for row in rows)
    assert [cell["tasks_run"] for cell in one["cells"]] == [2, 2, 2, 2]
    if two["plots"]:  # matplotlib (the plots extra) is there
        assert Path(two["plots"][0]).read_bytes()[:4] == b"\x89PNG"


def test_a_stopped_sweep_resumes_without_redoing_finished_tasks(
        spec: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    _sweep(capsys, spec, out, 1)
    whole = _results(out)
    table = out / TABLE
    lines = table.read_text(encoding="utf-8").splitlines(keepends=True)
    # stopped after three rows, in the middle of writing the fourth (its wall time)
    table.write_text("".join(lines[:4]) + lines[4][:-3], encoding="utf-8")
    resumed = _sweep(capsys, spec, out, 1)
    assert (resumed["ran"], resumed["kept"]) == (5, 3)
    assert _results(out) == whole
    again = _sweep(capsys, spec, out, 1)
    assert (again["ran"], again["kept"]) == (0, 8)


def test_a_grown_spec_runs_only_its_new_cells(
        spec: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    _sweep(capsys, spec, out, 1)
    spec.write_text(SPEC.replace("seeds: [3]", "seeds: [3, 4]"), encoding="utf-8")
    grown = _sweep(capsys, spec, out, 1)
    assert (grown["tasks"], grown["ran"], grown["kept"]) == (16, 8, 8)


@pytest.mark.parametrize(("text", "message"), [
    (SPEC.replace("levels:", "level:"), "grid.yaml: line 2: level: unknown field; did you mean "
                                        "'levels'?"),
    (SPEC.replace("[0, 2]", "[0, 7]"), "grid.yaml: line 2: levels.1: must be less than or "
                                       "equal to 6"),
    (SPEC.replace("[apartment]", "[apartmnet]"), "grid.yaml: line 1: worlds: no world "
                                                 "'apartmnet'"),
    (SPEC.replace("[3]", "[3, 3]"), "grid.yaml: line 3: seeds: 3 is listed twice; list each "
                                    "once"),
    (SPEC.replace("tasks: 2", "tasks: 0"), "grid.yaml: line 4: tasks: must be greater than or "
                                           "equal to 1"),
    (SPEC.replace("tasks: 2\n", ""), "grid.yaml: line 1: tasks: required field is missing"),
    (SPEC + "benchmarks: [gpsr]\n", "benchmarks.0: must be 'robustness'"),
    ("- apartment\n", "grid.yaml: line 1: the file must be a YAML mapping of fields"),
    ("worlds: [apartment\n", "grid.yaml: line 2, column 1: YAML syntax error"),
])
def test_a_bad_spec_is_one_line_naming_file_line_and_field(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, message: str) -> None:
    path = tmp_path / "grid.yaml"
    path.write_text(text, encoding="utf-8")
    assert main(["bench", "sweep", str(path), "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert message in error.replace("\n", " ") and "Traceback" not in error
    assert error.count("\n") == 1


def test_a_table_of_something_else_is_not_overwritten(
        spec: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / TABLE).write_text("name,score\nmine,1\n", encoding="utf-8")
    assert main(["bench", "sweep", str(spec), "--out", str(out)]) == 2
    assert "its columns are not a sweep table's" in capsys.readouterr().err
    assert (out / TABLE).read_text(encoding="utf-8") == "name,score\nmine,1\n"
    assert COLUMNS[0] == "benchmark"


def test_a_missing_spec_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "sweep", str(tmp_path / "none.yaml")]) == 2
    assert "none.yaml: cannot read it (no such file); check the path" in capsys.readouterr().err
