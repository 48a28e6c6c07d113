"""``homebot bench sweep SPEC.yaml``: a grid of benchmark runs as one table, resumable.

The spec (``homebot.bench.sweep_spec``) names the grid; each cell's seeded tasks run on the
workers (``homebot.bench.workers``) and each finished task becomes one row of
``OUT/tasks.csv`` at once, flushed, so a sweep stopped half-way (Ctrl-C, a lost machine)
keeps what it finished: run again, it redoes only the tasks without a finished row. A row
with an error (the task raised, or killed its worker twice) is kept in the table and run
again by the next resume. At the end the table is rewritten in the grid's order, and the
plots drawn beside it.

Columns: the task (benchmark, world, level, seed, fidelity, errands, tasks, mode, index,
run_seed), what the simulator's truth and the robot said (kind, done, reported_success,
verified, sim_time_s, struck, told_why), and how it ran (attempts: 2 when its first worker
died; error; worker and wall_s, which differ from run to run).
"""

from __future__ import annotations

import argparse
import csv
import io
import os
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.bench.robustness import (
    MODES,
    ErrandOutcome,
    ErrandTask,
    errand_tasks,
    run_errand_task,
)
from homebot.bench.sweep_spec import Cell, SweepSpec, load_sweep_spec, resolved_world
from homebot.bench.workers import (
    TaskOutcome,
    WorkerOptions,
    add_worker_options,
    each_outcome,
    worker_options,
)
from homebot.errors import BenchmarkError

__all__ = ["COLUMNS", "KEY_COLUMNS", "RUN_COLUMNS", "SweepResult", "SweepTask", "add_arguments",
           "cell_figures", "draw", "read_table", "run", "run_sweep", "sweep_tasks"]

#: The table's columns, in order.
COLUMNS = ("benchmark", "world", "level", "seed", "fidelity", "errands", "tasks", "mode",
           "index", "run_seed", "kind", "done", "reported_success", "verified", "sim_time_s",
           "struck", "told_why", "attempts", "error", "worker", "wall_s")
#: The columns that name a task: a row with the same values is the same task.
KEY_COLUMNS = COLUMNS[:9]
#: The columns that differ from run to run of the same task (not results).
RUN_COLUMNS = ("worker", "wall_s")
TABLE = "tasks.csv"
PLOT = "verified_by_level.png"

_Row = dict[str, str]
_Key = tuple[str, ...]


@dataclass(frozen=True)
class SweepTask:
    """One task of a sweep: its cell, and the unit a worker runs."""

    cell: Cell
    errands: str
    unit: ErrandTask

    @property
    def mode(self) -> str:
        return next(name for name, monitoring in MODES if monitoring == self.unit.monitoring)

    def key(self) -> _Key:
        return (self.cell.benchmark, self.cell.world, f"{self.cell.level:g}",
                str(self.cell.seed), str(self.cell.fidelity), self.errands,
                str(self.unit.tasks), self.mode, str(self.unit.index))

    def row(self, outcome: TaskOutcome[ErrandOutcome]) -> _Row:
        """The table's row for this task's outcome."""
        values = dict(zip(KEY_COLUMNS, self.key(), strict=True))
        values |= {"run_seed": str(self.unit.run_seed), "attempts": str(outcome.attempts),
                   "error": outcome.error or "", "worker": outcome.worker}
        found = outcome.value
        values |= {column: "" for column in ("kind", "done", "reported_success", "verified",
                                             "sim_time_s", "struck", "told_why", "wall_s")}
        if found is not None:
            values |= {"kind": found.kind, "done": str(found.done),
                       "reported_success": str(found.success), "verified": str(found.verified),
                       "sim_time_s": f"{found.sim_time:.3f}", "struck": ";".join(found.struck),
                       "told_why": str(found.told_why), "wall_s": f"{found.wall:.4f}"}
        return values


def sweep_tasks(spec: SweepSpec, spec_path: Path) -> list[SweepTask]:
    """Every task of the spec's grid, cell by cell."""
    return [SweepTask(cell, spec.errands, unit) for cell in spec.cells()
            for unit in errand_tasks(resolved_world(spec_path, cell.world), spec.tasks,
                                     cell.seed, cell.level, cell.fidelity, spec.errands)]


def read_table(path: Path) -> list[_Row]:
    """The rows of a sweep table; a row cut short (the sweep was stopped while writing it)
    is left out. A file that is no sweep table raises ``BenchmarkError``."""
    if not path.exists():
        return []
    try:
        text = path.read_text(encoding="utf-8")
        lines = list(csv.reader(io.StringIO(text, newline="")))
    except (OSError, UnicodeDecodeError, csv.Error) as error:
        raise BenchmarkError(f"{path}: cannot be read as a sweep table ({error}); move it "
                             "away or choose another --out") from None
    if lines and not text.endswith("\n"):  # its last row was being written at the stop
        lines.pop()
    if not lines:
        return []
    if tuple(lines[0]) != COLUMNS:
        raise BenchmarkError(f"{path}: its columns are not a sweep table's ({', '.join(COLUMNS)});"
                             " move it away or choose another --out")
    return [dict(zip(COLUMNS, line, strict=True)) for line in lines[1:]
            if len(line) == len(COLUMNS)]


def _write_table(path: Path, rows: Iterable[Mapping[str, str]]) -> None:
    """Write the whole table at once: a new file put in place, so a stop never halves it."""
    partial = path.with_name(path.name + ".partial")
    with partial.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    os.replace(partial, path)


def _key(row: Mapping[str, str]) -> _Key:
    return tuple(row[column] for column in KEY_COLUMNS)


@dataclass(frozen=True)
class SweepResult:
    """A finished sweep: its table's rows in the grid's order, and what this run did."""

    table: Path
    rows: list[_Row]  #: the grid's rows, in its order
    ran: int  #: tasks run now
    kept: int  #: finished tasks found in the table and not run again
    others: int  #: rows of cells no longer in the spec, kept at the table's end


def run_sweep(spec_path: Path, out: Path, options: WorkerOptions) -> SweepResult:
    """Run the spec's tasks that the table in ``out`` does not hold finished, row by row."""
    spec = load_sweep_spec(spec_path)
    if out.exists() and not out.is_dir():
        raise BenchmarkError(f"--out {out}: is a file; give a folder for the table and plots")
    out.mkdir(parents=True, exist_ok=True)
    table = out / TABLE
    tasks = sweep_tasks(spec, spec_path)
    grid = {task.key() for task in tasks}
    found = read_table(table)
    finished = {_key(row): row for row in found if not row["error"] and _key(row) in grid}
    others = [row for row in found if _key(row) not in grid]
    _write_table(table, [*finished.values(), *others])
    todo = [task for task in tasks if task.key() not in finished]
    done: dict[_Key, _Row] = {}
    with table.open("a", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, COLUMNS)
        for outcome in each_outcome(run_errand_task, [task.unit for task in todo], options,
                                    "sweep"):
            row = todo[outcome.index].row(outcome)
            writer.writerow(row)
            handle.flush()  # a stop now keeps this row
            done[_key(row)] = row
    rows = [finished.get(task.key()) or done[task.key()] for task in tasks]
    _write_table(table, [*rows, *others])
    return SweepResult(table, rows, len(todo), len(finished), len(others))


def cell_figures(rows: Sequence[Mapping[str, str]]) -> list[dict[str, Any]]:
    """Per cell and mode, in the rows' order: tasks, verified by the truth, retried, errors."""
    cells: dict[_Key, dict[str, Any]] = {}
    for row in rows:
        key = (*_key(row)[:8],)
        figures = cells.setdefault(key, {
            **{column: row[column] for column in KEY_COLUMNS[:8]},
            "tasks_run": 0, "verified": 0, "retried": 0, "errors": 0})
        figures["tasks_run"] += 1
        figures["verified"] += row["verified"] == "True"
        figures["retried"] += int(row["attempts"]) > 1
        figures["errors"] += bool(row["error"])
    for figures in cells.values():
        figures["verified_rate"] = round(figures["verified"] / figures["tasks_run"], 4)
    return list(cells.values())


def draw(result: SweepResult, out: Path) -> list[str]:
    """The sweep's plots beside its table (their paths); none without matplotlib."""
    import importlib.util

    if importlib.util.find_spec("matplotlib") is None:
        from homebot.bench.plots import INSTALL

        print(f"no plots: they need matplotlib, the 'plots' extra ({INSTALL})",
              file=sys.stderr)
        return []
    from homebot.bench.plots import save, sweep_figure

    path = out / PLOT
    save(sweep_figure(cell_figures(result.rows)), path)
    return [str(path)]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    # checked when read (a missing file is one line then), so the command line parses alone
    parser.add_argument("spec", type=Path, metavar="SPEC.yaml",
                        help="the sweep spec: benchmarks, worlds, levels, seeds, fidelities, "
                             "tasks (docs: many cores and machines)")
    parser.add_argument("--out", type=Path, default=None, metavar="DIR",
                        help="the folder of the table (tasks.csv) and plots; a sweep there is "
                             "resumed (default: the spec's name beside it)")
    add_worker_options(parser)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Run (or resume) the sweep, draw its plots and print its cells; returns the figures."""
    out = args.out if args.out is not None else args.spec.with_suffix("")
    try:
        result = run_sweep(args.spec, out, worker_options(args))
    except KeyboardInterrupt:  # Ctrl-C: a stop, not a crash; the finished rows are kept
        print(f"sweep stopped: {len(read_table(out / TABLE))} finished rows are in "
              f"{out / TABLE}; run the same command again to go on", file=sys.stderr)
        raise SystemExit(130) from None
    plots = draw(result, out)
    cells = cell_figures(result.rows)
    if console is not None:
        table = Table(title=f"Sweep {args.spec}: {len(result.rows)} tasks ({result.ran} run now, "
                            f"{result.kept} kept from before)")
        for column in ("benchmark", "world", "level", "seed", "fidelity", "mode", "verified",
                       "retried", "errors"):
            table.add_column(column)
        for cell in cells:
            table.add_row(cell["benchmark"], cell["world"], cell["level"], cell["seed"],
                          cell["fidelity"], cell["mode"],
                          f"{cell['verified']}/{cell['tasks_run']}", str(cell["retried"]),
                          str(cell["errors"]))
        console.print(table)
        console.print(f"table: {result.table}" + "".join(f"\nplot: {plot}" for plot in plots))
    return {"benchmark": "sweep", "spec": str(args.spec), "table": str(result.table),
            "plots": plots, "tasks": len(result.rows), "ran": result.ran, "kept": result.kept,
            "other_rows": result.others,
            "retried": sum(int(row["attempts"]) > 1 for row in result.rows),
            "errors": sum(bool(row["error"]) for row in result.rows), "cells": cells}
