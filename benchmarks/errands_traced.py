"""Everyday errands for the embodied robot, monitored mode only, each task traced.

``bench robustness`` runs every task twice (monitored and plain) and prints totals; this
runs the same seeded errands once, monitored, and prints each task's outcome and, for a
failure, why (the robot's reason and its last words) beside what the simulator's truth
shows, then the totals with the hands in the loop as JSON.

    PYTHONPATH=src python benchmarks/errands_traced.py WORLD TASKS SEED
"""

from __future__ import annotations

import json
import sys
import time

from homebot.app import Fidelity, RunSettings, build_run, disturbed
from homebot.bench.robustness import ModeResult, errand_set
from homebot.navigation import Navigator
from homebot.world import World


def main(world_name: str, tasks: int, seed: int) -> None:
    world = World.load(world_name)
    navigator = Navigator(world)
    result = ModeResult("monitored + recovery")
    for index, errand in enumerate(errand_set(world, tasks, seed)):
        run = build_run(RunSettings(world=world, seed=seed * 100_003 + index,
                                    disturbances=disturbed(1.0), navigator=navigator,
                                    fidelity=Fidelity.EMBODIED))
        errand.arrange(run.simulation)
        started = time.perf_counter()
        report = run.run(errand.task)
        wall = time.perf_counter() - started
        verified = errand.done(run.simulation) and report.success
        result.tasks += 1
        result.verified += verified
        result.sim_times.append(report.sim_time)
        result.wall_times.append(wall)
        result.count_hands(run.simulation.events.events)
        counts = result.by_kind.setdefault(str(errand.kind), [0, 0])
        counts[0] += 1
        counts[1] += verified
        why = "" if verified else (f"{report.reason!r} said {report.speech[-1:]} truth: "
                                   f"{'done' if errand.done(run.simulation) else 'not done'}")
        print(index, errand.kind.value, "OK" if verified else "FAIL",
              f"{report.sim_time:.1f} s", f"{wall:.1f} s wall", why, flush=True)
    print(json.dumps(result.to_dict()))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
