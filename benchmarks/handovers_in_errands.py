"""Hand-over and receive inside embodied errands, judged by the simulator's truth.

    PYTHONPATH=src python benchmarks/handovers_in_errands.py apartment --seeds 104,105

Per seed, ``homebot.trials.errands`` draws ``--errands`` errands; each FETCH (ends in
``give``) and TAKE (starts with ``receive``) one runs alone in an embodied run. A
hand-over succeeded when the truth has the object with the person (``Errand.done``); a
receive succeeded when the person let go into the robot's hand (the simulator's
``sim.person`` event) and the object no longer is with them. ASK errands are skipped.
"""

from __future__ import annotations

import argparse

from homebot.app import Fidelity, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.sim import PERSON_PREFIX
from homebot.trials.errands import ErrandKind, errands
from homebot.world import World


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("world")
    parser.add_argument("--seeds", default="104,105", help="comma-separated seeds")
    parser.add_argument("--errands", type=int, default=4, help="errands drawn per seed")
    args = parser.parse_args()
    world = World.load(args.world)
    navigator = Navigator(world)
    tally = {ErrandKind.FETCH: [0, 0], ErrandKind.TAKE: [0, 0]}
    for seed in (int(text) for text in args.seeds.split(",")):
        for index, errand in enumerate(errands(world, args.errands, seed)):
            if errand.kind is ErrandKind.ASK or errand.obj is None:
                continue
            run = build_run(RunSettings(world=world, seed=seed, navigator=navigator,
                                        fidelity=Fidelity.EMBODIED))
            errand.arrange(run.simulation)
            report = run.run(errand.task)
            truth = run.simulation
            where = truth.object_location.get(errand.obj, "")
            if errand.kind is ErrandKind.FETCH:
                succeeded = errand.done(truth)  # the person (the operator by name) holds it
            else:
                succeeded = not where.startswith(PERSON_PREFIX) and any(
                    event.kind == "sim.person" and event.data.get("did") == "let go"
                    for event in truth.events.events)
            tally[errand.kind][0] += succeeded
            tally[errand.kind][1] += 1
            print(f"seed {seed} errand {index} {errand.kind.value}: "
                  f"{'ok' if succeeded else 'FAILED'} (task {report.success}"
                  f"{', ' + report.reason if report.reason else ''})", flush=True)
    for kind, (ok, total) in tally.items():
        print(f"{'hand-over' if kind is ErrandKind.FETCH else 'receive'}: {ok}/{total}")


if __name__ == "__main__":
    main()
