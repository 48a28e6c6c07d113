"""A long-running simulation: memory over thousands of consecutive tasks in one home.

One ``Run`` carries out fetch-and-deliver tasks one after the other (10 000 by
default) with its event log bounded (``EventLog.keep``: at most the latest events stay in
memory; give ``--events FILE`` to stream every event to a file as well). After each task
someone puts the object back where it belongs, as a household would, so every task is a
whole fetch; ``--no-put-back`` leaves it with its person, so that after the first few
hundred tasks every task is a search of the whole home that fails (the recovery path).
The resident set size is read from ``/proc/self/status`` after a warm-up, at ten points
on the way (the growth curve) and at the end; its growth is the figure. Nothing is
asserted.
"""

from __future__ import annotations

import argparse
import gc
import time
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run
from homebot.bench.arguments import count, seed
from homebot.navigation import Navigator
from homebot.trials.fetch import fetch_tasks
from homebot.world import World

__all__ = ["add_arguments", "resident_mb", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--tasks", type=count("--tasks", 1, 1_000_000), default=10_000,
                        help="consecutive tasks (default 10000)")
    parser.add_argument("--warm-up", type=count("--warm-up", 0, 100_000), default=200,
                        help="tasks before the first reading (default 200)")
    parser.add_argument("--keep", type=count("--keep", 1, 10_000_000), default=5000,
                        help="events kept in memory (default 5000)")
    parser.add_argument("--events", type=Path, default=None,
                        help="stream every event to this JSON-lines file")
    parser.add_argument("--seed", type=seed, default=5)
    parser.add_argument("--no-put-back", dest="put_back", action="store_false",
                        help="leave each delivered object with its person: after the first "
                             "few hundred tasks, every task is a search of the whole home that "
                             "fails (the recovery path, over and over)")


def resident_mb() -> float | None:
    """This process's resident set size in MB (Linux), or None where it cannot be read."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        return None
    return None


def _growth(before: float | None, after: float | None = None) -> float | None:
    """MB the resident set grew since ``before`` (to ``after``, else now, after a collection)."""
    if after is None:
        gc.collect()
        after = resident_mb()
    return None if before is None or after is None else round(after - before, 2)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Run the tasks; report the resident memory after the warm-up and at the end."""
    world = World.load("apartment")
    navigator = Navigator(world)
    simulation_run = build_run(RunSettings(world=world, seed=args.seed, navigator=navigator))
    events = simulation_run.simulation.events
    events.keep = args.keep
    simulation_run.simulation.trail_keep = args.keep  # the robot's drawn path, likewise
    stream = args.events.open("w", encoding="utf-8") if args.events is not None else None
    events.stream = stream
    tasks = fetch_tasks(world, min(args.tasks, 500), args.seed)
    succeeded = 0
    before: float | None = None
    curve: list[tuple[int, float | None]] = []
    every = max(1, args.tasks // 10)
    began = time.perf_counter()
    try:
        for index in range(args.warm_up + args.tasks):
            if index == args.warm_up:
                gc.collect()
                before = resident_mb()
                began = time.perf_counter()
            fetch = tasks[index % len(tasks)]
            report = simulation_run.run(fetch.task)
            succeeded += index >= args.warm_up and report.success
            if args.put_back:
                simulation_run.simulation.put_object(fetch.obj,
                                                     world.objects[fetch.obj].placement)
            done = index + 1 - args.warm_up
            if done > 0 and done % every == 0 and done < args.tasks:
                curve.append((done, _growth(before)))
    finally:
        if stream is not None:
            stream.close()
    seconds = time.perf_counter() - began
    gc.collect()
    after = resident_mb()
    growth = _growth(before, after)
    figures: dict[str, Any] = {
        "benchmark": "long_run", "tasks": args.tasks, "warm_up": args.warm_up,
        "objects_put_back": args.put_back,
        "events_kept": args.keep, "events_recorded": events.count,
        "events_in_memory": len(events.events), "succeeded": succeeded,
        "rss_mb_after_warm_up": None if before is None else round(before, 1),
        "rss_mb_at_end": None if after is None else round(after, 1),
        "rss_growth_mb": growth,
        "rss_growth_curve_mb": [[done, value] for done, value in curve] + [[args.tasks, growth]],
        "ms_per_task": round(1000 * seconds / args.tasks, 3),
    }
    if console is not None:
        console.print(f"[bold]long run[/]: {args.tasks} consecutive tasks in one home "
                      f"({succeeded} succeeded), {events.count} events recorded, "
                      f"{len(events.events)} kept in memory; resident memory "
                      f"{figures['rss_mb_after_warm_up']} MB after {args.warm_up} tasks, "
                      f"{figures['rss_mb_at_end']} MB at the end (growth {growth} MB); "
                      f"{figures['ms_per_task']} ms per task")
        console.print("growth on the way (tasks: MB): " + ", ".join(
            f"{done}: {value}" for done, value in figures["rss_growth_curve_mb"]))
    return figures
