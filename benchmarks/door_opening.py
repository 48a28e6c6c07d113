"""Shut doors opened by the embodied robot's arm inside a task, judged by the simulator.

    PYTHONPATH=src python benchmarks/door_opening.py --seeds 11 12 [worlds...]

For every door of every world (default: the shipped worlds) no wider than 1 m (wider
ones are arches), on each of its sides: the door is shut (every other one open), the
robot stands 0.6 m before it, facing it, where navigation stops before a door, and the
executive runs the one-step task ``open_door`` (no recovery: nobody is asked). The side
the leaf swings away from is counted apart and not run: there the robot declines by its
map (its arm does not push doors open; ``tests/embodied/test_doors_opened_by_the_arm.py``
shows it). Where it tries, the door counts as opened only when the
simulator's truth has it open and its physics swung the leaf (``sim.door``); prints per
attempt and in total: opened / tried, simulated seconds per attempt, the robot's
collisions with the leaf, and the reasons given when not opened.
"""

from __future__ import annotations

import argparse
import collections
import json
import time

from homebot.app import Fidelity, RunSettings, build_run
from homebot.embodied.hands import ArmedBodyRobot
from homebot.task import Step, Task
from homebot.world import DoorState, World, shipped_world_names

_BEFORE = 0.6  #: metres before the door, as navigation leaves the robot
_WIDEST = 1.0  #: metres: a wider doorway is an arch, with no leaf


def _attempt(world: World, door: str, room: str, seed: int) -> dict[str, object]:
    run = build_run(RunSettings(world=world, seed=seed, fidelity=Fidelity.EMBODIED,
                                recovery=False))
    sim = run.simulation
    for name in sim.door_state:
        sim.door_state[name] = DoorState.OPEN
    sim.door_state[door] = DoorState.CLOSED
    stand = world.point_before_door(door, room, _BEFORE)
    assert run.body is not None and isinstance(run.robot, ArmedBodyRobot)
    run.body.teleport(stand)  # type: ignore[attr-defined]
    run.robot.localisation.initialise(stand, spread=0.05, angle_spread=0.05)
    began, wall = sim.clock.now(), time.perf_counter()
    run.run(Task((Step("open_door", {"door": door}),)))
    attempts = [e.data for e in sim.events.events if e.kind == "robot.open_door"]
    swung = any(e.kind == "sim.door" and e.data.get("door") == door
                for e in sim.events.events)
    return {"door": door, "from": room, "seed": seed,
            "opened": sim.door_state[door] is DoorState.OPEN and swung,
            "declined": bool(attempts) and "opens away" in str(attempts[0]["reason"]),
            "reasons": [a["reason"] for a in attempts],
            "seconds": round(sim.clock.now() - began, 1),
            "wall_s": round(time.perf_counter() - wall, 1),
            "collisions": [c for c in sim.collisions if str(c["with"]).startswith("door")]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("worlds", nargs="*")
    parser.add_argument("--seeds", type=int, nargs="+", default=[11])
    args = parser.parse_args()
    results = []
    for name in args.worlds or shipped_world_names():
        world = World.load(name)
        for door, model in sorted(world.doors.items()):
            if model.width > _WIDEST:
                continue
            for room in model.rooms:
                if room != (model.swings_into or model.rooms[0]):
                    results.append({"world": world.name, "door": door, "from": room,
                                    "declined": True, "opened": False, "reasons": [],
                                    "seconds": 0.0, "wall_s": 0.0, "collisions": []})
                    continue
                for seed in args.seeds:
                    result = {"world": world.name, **_attempt(world, door, room, seed)}
                    print(json.dumps(result), flush=True)
                    results.append(result)
    tried = [r for r in results if not r["declined"]]
    opened = [r for r in tried if r["opened"]]
    reasons = collections.Counter(str(reason) for r in tried if not r["opened"]
                                  for reason in r["reasons"][:1])
    print(json.dumps({
        "seeds": args.seeds, "door_sides": len(results),
        "declined_swings_away": len(results) - len(tried),
        "tried": len(tried), "opened": len(opened),
        "mean_seconds_opened": round(sum(float(r["seconds"]) for r in opened) /
                                     len(opened), 1) if opened else None,
        "mean_seconds_tried": round(sum(float(r["seconds"]) for r in tried) /
                                    max(len(tried), 1), 1),
        "collisions": sum(len(r["collisions"]) for r in results),  # type: ignore[arg-type]
        "not_opened_because": dict(reasons),
        "wall_s": round(sum(float(r["wall_s"]) for r in results), 1)}))


if __name__ == "__main__":
    main()
