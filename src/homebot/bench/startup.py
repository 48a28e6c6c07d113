"""One-shot commands as a person runs them: a fresh ``homebot`` process each time, timed
from start to exit (wall and CPU), beside a bare Python start on the same machine.

Each round runs every command once, in turn, so a change in the machine's load falls on
all of them alike; the load average is given beside the figures. The world's names are
kept between processes (``homebot.app.world_names``), so ``parse`` is timed with them
kept, after one cold run (an empty cache) that is reported apart. Bytecode is written and
read as in an installed homebot (``PYTHONDONTWRITEBYTECODE`` is cleared for the runs).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.app.cache import CACHE_DIRECTORY_VARIABLE
from homebot.bench.arguments import count
from homebot.errors import HomebotError
from homebot.progress import track

__all__ = ["COMMANDS", "add_arguments", "run"]

#: what is timed: a name, and ``homebot``'s arguments (None: a bare Python start)
COMMANDS: dict[str, list[str] | None] = {
    "python -c pass (the floor)": None,
    "homebot --help": ["--help"],
    "homebot parse 'bring me a coke' --json": ["parse", "bring me a coke", "--json"],
    "homebot kb query animals class_extension birds --json":
        ["kb", "query", "animals", "class_extension", "birds", "--json"],
}
_HOMEBOT = "import sys\nfrom homebot.cli import main\nsys.exit(main())"
TARGET_S = 0.15  #: issue 35: each one-shot command within this, wall


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--runs", type=count("--runs", 1, 1000), default=20,
                        help="timed runs of each command")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Median and 90th percentile wall and CPU seconds per command, the parse command's
    cold first run, and the load average before and after."""
    with tempfile.TemporaryDirectory(prefix="homebot-startup-") as cache:
        environment = {key: value for key, value in os.environ.items()
                       if key != "PYTHONDONTWRITEBYTECODE"}
        environment[CACHE_DIRECTORY_VARIABLE] = cache
        load_before = os.getloadavg()
        cold_parse = _timed(COMMANDS["homebot parse 'bring me a coke' --json"], environment)
        for arguments in COMMANDS.values():  # bytecode written, caches filled
            _timed(arguments, environment)
        samples: dict[str, list[tuple[float, float]]] = {name: [] for name in COMMANDS}
        for _ in track(range(args.runs), "rounds of one-shot commands"):
            for name, arguments in COMMANDS.items():
                samples[name].append(_timed(arguments, environment))
        load_after = os.getloadavg()
    figures: dict[str, Any] = {name: _summary(runs) for name, runs in samples.items()}
    figures["parse, cold (no names kept)"] = {"wall_s": round(cold_parse[0], 3),
                                              "cpu_s": round(cold_parse[1], 3)}
    result = {"benchmark": "startup", "runs": args.runs, "target_wall_s": TARGET_S,
              "load_average_before_after": [round(load_before[0], 2), round(load_after[0], 2)],
              "figures": figures}
    if console is not None:
        console.print(f"load average (1 min) {load_before[0]:.2f} before, "
                      f"{load_after[0]:.2f} after; target {TARGET_S} s wall")
        for name, values in figures.items():
            console.print(f"{name}: {values}")
    return result


def _timed(arguments: list[str] | None, environment: dict[str, str]) -> tuple[float, float]:
    """Wall and CPU (user + system) seconds of one fresh process."""
    command = [sys.executable, "-c", "pass"] if arguments is None else [
        sys.executable, "-c", _HOMEBOT, *arguments]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    began = time.perf_counter()
    done = subprocess.run(command, env=environment, cwd=Path.home(),
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, check=False)
    wall = time.perf_counter() - began
    if done.returncode != 0:  # an error's start-up is not the command's
        raise HomebotError(f"bench startup: {' '.join(arguments or ['python'])} exited "
                           f"{done.returncode}: {done.stderr.decode(errors='replace')[-300:]}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def _summary(runs: list[tuple[float, float]]) -> dict[str, float]:
    walls = sorted(wall for wall, _ in runs)
    cpus = sorted(cpu for _, cpu in runs)
    return {"median_wall_s": round(statistics.median(walls), 3),
            "p90_wall_s": round(walls[int(0.9 * (len(walls) - 1))], 3),
            "median_cpu_s": round(statistics.median(cpus), 3)}
