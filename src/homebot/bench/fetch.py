"""Wall time of one simulated fetch-and-deliver task, cold (every cache cleared) and warm.

pyrobosim's fastest stock setting takes ~300 ms a task: quoted from issue 1's survey, not
measured here, and not divided into a ratio. Cold: the navigator's A* cache, the plan
cache and ``World.room_at``'s memory are cleared before every task; warm: all shared
between tasks (the ratio of the two is measured in this run).
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run
from homebot.bench.arguments import add_fidelity_option, count, seed
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.sim import PlanCache
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--tasks", type=count("--tasks", 1, 20_000), default=200,
                        help="tasks to time")
    parser.add_argument("--seed", type=seed, default=3)
    add_fidelity_option(parser)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Median and 95th percentile wall time per task, with and without warm path caches,
    and how much faster than real time the simulated tasks ran (simulated seconds per wall
    second, and per CPU second of this process)."""
    world = World.load("apartment")
    navigator = Navigator(world)
    figures: dict[str, Any] = {}
    for label, shared in (("cold (every cache cleared before each task)", False),
                          ("warm (navigator, plans and room_at shared)", True)):
        samples, simulated, delivered_count, cpu = [], 0.0, 0, 0.0
        plans = PlanCache(navigator)
        world.forget_cached()
        navigator._cache.clear()
        for index, fetch in enumerate(track(fetch_tasks(world, args.tasks, args.seed),
                                            f"fetch tasks, {label.split()[0]}")):
            if not shared:
                navigator._cache.clear()
                world.forget_cached()
                plans.clear()
            run_ = build_run(RunSettings(
                world=world, seed=index, navigator=navigator, plans=plans, fidelity=args.fidelity))
            began, cpu_began = time.perf_counter(), time.process_time()
            report = run_.run(fetch.task)
            samples.append(time.perf_counter() - began)
            cpu += time.process_time() - cpu_began
            simulated += report.sim_time
            delivered_count += delivered(run_.simulation, fetch)
        samples.sort()
        figures[label] = {"median_ms": round(1000 * statistics.median(samples), 3),
                          "p95_ms": round(1000 * samples[int(0.95 * (len(samples) - 1))], 3),
                          "faster_than_real_time": round(simulated / sum(samples), 1),
                          # all of this process's threads: near what one core alone would
                          # give, and far less sensitive to the machine's load than wall time
                          "faster_than_real_time_per_cpu_second": round(simulated / cpu, 1),
                          "delivered": delivered_count}
    cold, warm = (figures[name]["median_ms"] for name in figures)
    figures["warm_speedup_in_this_run"] = round(cold / warm, 2) if warm else None
    if console is not None:
        for name, values in figures.items():
            console.print(f"fetch-and-deliver, {name}: {values}")
    return {"benchmark": "fetch", "tasks": args.tasks, "fidelity": str(args.fidelity),
            "figures": figures}
