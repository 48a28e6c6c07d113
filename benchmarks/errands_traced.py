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

from homebot.app import Fidelity
from homebot.bench.robustness import ModeResult, errand_set, run_errand
from homebot.navigation import Navigator
from homebot.world import World


def main(world_name: str, tasks: int, seed: int) -> None:
    world = World.load(world_name)
    navigator = Navigator(world)
    result = ModeResult("monitored + recovery")
    for index, errand in enumerate(errand_set(world, tasks, seed)):
        ran = run_errand(world, errand, seed * 100_003 + index, navigator=navigator,
                         fidelity=Fidelity.EMBODIED)
        result.add(ran.outcome(hands=True))
        report = ran.report
        why = "" if ran.verified else (f"{report.reason!r} said {report.speech[-1:]} truth: "
                                       f"{'done' if ran.done else 'not done'}")
        outcome = "OK" if ran.verified else "IMPOSSIBLE" if ran.impossible else "FAIL"
        print(index, errand.kind.value, outcome,
              f"{report.sim_time:.1f} s", f"{ran.wall:.1f} s wall", why, flush=True)
    print(json.dumps(result.to_dict()))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
