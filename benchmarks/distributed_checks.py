"""The figures of running benchmarks on many workers (docs/scaling.md), each check a command:

    PYTHONPATH=src python benchmarks/distributed_checks.py speedup [TASKS] [FIDELITY]
        bench robustness with 1 and with 2 workers: wall and CPU seconds, the load beside
        them, and whether the figures are identical apart from timings
    PYTHONPATH=src python benchmarks/distributed_checks.py cluster SPEC.yaml
        a Dask scheduler and two workers started on 127.0.0.1, the sweep sent there with
        --cluster, and its table compared with the same sweep run by a local pool
    PYTHONPATH=src python benchmarks/distributed_checks.py kill SPEC.yaml ROWS
        the sweep on 2 local workers; once ROWS rows are written, one worker process is
        killed with SIGKILL; the rows marked retried (attempts 2) are printed
    PYTHONPATH=src python benchmarks/distributed_checks.py resume SPEC.yaml ROWS
        the sweep stopped with Ctrl-C (SIGINT) once ROWS rows are written, run again, and
        its table compared with an uninterrupted run's

Each check runs ``homebot`` in a fresh process, as a person would, and reads what it wrote.
Run them one at a time: the machine's two cores are the thing measured.
"""

from __future__ import annotations

import csv
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import psutil

from homebot.bench.sweep import RUN_COLUMNS, TABLE

BIN = Path(sys.executable).parent  # the venv's commands: homebot, dask
HOMEBOT = [str(BIN / "homebot")]


def _load() -> str:
    return "load average " + ", ".join(f"{value:.2f}" for value in os.getloadavg())


def _homebot(*arguments: str) -> tuple[dict[str, Any], float, float]:
    """Run homebot with --json: its figures, wall seconds, CPU seconds of it and its children."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    done = subprocess.run([*HOMEBOT, *arguments, "--json"], capture_output=True, text=True,
                          check=True)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return json.loads(done.stdout), wall, cpu


def _results(table: Path) -> list[dict[str, str]]:
    with table.open(newline="", encoding="utf-8") as handle:
        return [{column: value for column, value in row.items() if column not in RUN_COLUMNS}
                for row in csv.DictReader(handle)]


def speedup(tasks: int, fidelity: str) -> None:
    figures = {}
    for workers in (1, 2):
        print(f"{workers} worker(s): {_load()} before", flush=True)
        result, wall, cpu = _homebot("bench", "robustness", "--tasks", str(tasks),
                                     "--fidelity", fidelity, "--workers", str(workers))
        for mode in result["modes"]:
            del mode["median_wall_ms"]
        figures[workers] = result
        print(f"{workers} worker(s): {wall:.1f} s wall, {cpu:.1f} s CPU (with its workers), "
              f"{_load()} after", flush=True)
        figures[f"wall {workers}"] = wall
    print(f"speed-up {figures['wall 1'] / figures['wall 2']:.2f}x; figures identical: "
          f"{figures[1] == figures[2]}")


def _rows(table: Path) -> int:
    if not table.exists():
        return 0
    return max(len(table.read_text(encoding="utf-8").splitlines()) - 1, 0)


def _wait_for_rows(process: subprocess.Popen[str], table: Path, rows: int) -> None:
    while process.poll() is None and _rows(table) < rows:
        time.sleep(0.2)  # the check watches a file another process writes


def _sweep_process(spec: Path, out: Path, *arguments: str) -> subprocess.Popen[str]:
    return subprocess.Popen([*HOMEBOT, "bench", "sweep", str(spec), "--out", str(out),
                             "--json", *arguments], stdout=subprocess.PIPE, text=True)


def cluster(spec: Path) -> None:
    work = Path(tempfile.mkdtemp(prefix="homebot-cluster-"))
    scheduler_file = work / "scheduler.json"
    environment = os.environ | {"DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0",
                                "DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION": "1.0",
                                "DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED": "False"}
    scheduler = subprocess.Popen([str(BIN / "dask"), "scheduler", "--host", "127.0.0.1",
                                  "--port", "0", "--dashboard-address", "127.0.0.1:0",
                                  "--scheduler-file", str(scheduler_file)],
                                 env=environment, stderr=subprocess.DEVNULL)
    try:
        while not scheduler_file.exists():
            time.sleep(0.2)  # the scheduler writes its address when it listens
        address = json.loads(scheduler_file.read_text(encoding="utf-8"))["address"]
        worker = subprocess.Popen([str(BIN / "dask"), "worker", address,
                                   "--nworkers", "2", "--nthreads", "1", "--host", "127.0.0.1",
                                   "--dashboard-address", "127.0.0.1:0"],
                                  env=environment, stderr=subprocess.DEVNULL)
        try:
            print(f"scheduler at {address}; {_load()}", flush=True)
            remote, wall, _ = _homebot("bench", "sweep", str(spec), "--out",
                                       str(work / "cluster"), "--cluster", address)
            print(f"--cluster: {remote['tasks']} tasks in {wall:.1f} s, "
                  f"{remote['errors']} errors", flush=True)
            local, wall, _ = _homebot("bench", "sweep", str(spec), "--out", str(work / "local"),
                                      "--workers", "2")
            print(f"local pool: {local['tasks']} tasks in {wall:.1f} s", flush=True)
            same = _results(work / "cluster" / TABLE) == _results(work / "local" / TABLE)
            print(f"tables identical apart from worker and wall time: {same}")
        finally:
            worker.send_signal(signal.SIGINT)
            worker.wait(60)
    finally:
        scheduler.send_signal(signal.SIGINT)
        scheduler.wait(60)
        shutil.rmtree(work)


def kill(spec: Path, rows: int) -> None:
    out = Path(tempfile.mkdtemp(prefix="homebot-kill-"))
    sweep = _sweep_process(spec, out, "--workers", "2")
    _wait_for_rows(sweep, out / TABLE, rows)
    workers = [child for child in psutil.Process(sweep.pid).children(recursive=True)
               if "spawn_main" in " ".join(child.cmdline())]
    print(f"{_rows(out / TABLE)} rows written; killing worker process {workers[0].pid} "
          f"(of {[child.pid for child in workers]}) with SIGKILL", flush=True)
    workers[0].send_signal(signal.SIGKILL)
    output, _ = sweep.communicate()
    figures = json.loads(output)
    print(f"sweep finished: exit {sweep.returncode}, {figures['tasks']} tasks, "
          f"{figures['retried']} retried, {figures['errors']} errors")
    for row in csv.DictReader((out / TABLE).open(newline="", encoding="utf-8")):
        if row["attempts"] != "1" or row["error"]:
            print("  ", {column: row[column] for column in
                         ("world", "level", "seed", "mode", "index", "verified", "attempts",
                          "error")})
    _homebot("bench", "sweep", str(spec), "--out", str(out / "calm"), "--workers", "2")
    results = [{**row, "attempts": "-"} for row in _results(out / TABLE)]
    print("results identical to a sweep without the kill (attempts aside): "
          f"{results == [{**row, 'attempts': '-'} for row in _results(out / 'calm' / TABLE)]}")
    shutil.rmtree(out)


def resume(spec: Path, rows: int) -> None:
    work = Path(tempfile.mkdtemp(prefix="homebot-resume-"))
    whole, wall, _ = _homebot("bench", "sweep", str(spec), "--out", str(work / "whole"),
                              "--workers", "2")
    print(f"uninterrupted: {whole['tasks']} tasks in {wall:.1f} s", flush=True)
    sweep = _sweep_process(spec, work / "stopped", "--workers", "2")
    _wait_for_rows(sweep, work / "stopped" / TABLE, rows)
    sweep.send_signal(signal.SIGINT)
    sweep.communicate()
    print(f"stopped with Ctrl-C: exit {sweep.returncode}, "
          f"{_rows(work / 'stopped' / TABLE)} rows kept", flush=True)
    resumed, wall, _ = _homebot("bench", "sweep", str(spec), "--out", str(work / "stopped"),
                                "--workers", "2")
    print(f"resumed: {resumed['ran']} run, {resumed['kept']} kept, in {wall:.1f} s; table "
          f"identical to the uninterrupted one apart from worker and wall time: "
          f"{_results(work / 'stopped' / TABLE) == _results(work / 'whole' / TABLE)}")
    shutil.rmtree(work)


if __name__ == "__main__":
    check, *rest = sys.argv[1:]
    if check == "speedup":
        speedup(int(rest[0]) if rest else 1000, rest[1] if len(rest) > 1 else "symbolic")
    elif check == "cluster":
        cluster(Path(rest[0]))
    elif check == "kill":
        kill(Path(rest[0]), int(rest[1]))
    elif check == "resume":
        resume(Path(rest[0]), int(rest[1]))
    else:
        sys.exit(f"unknown check {check!r}: speedup, cluster, kill or resume")
