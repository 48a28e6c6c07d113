"""Shut doors opened by the embodied robot's arm inside a task, judged by the simulator.

    PYTHONPATH=src python benchmarks/door_opening.py --seeds 11 12 [worlds...]
    PYTHONPATH=src python benchmarks/door_opening.py --fetch --seeds 31 32 33

``--fetch``: a whole fetch through a shut door that nobody will open (see ``_fetch``).

For every door of every world (default: the shipped worlds) no wider than 1 m (wider
ones are arches), on each of its sides: the door is shut (every other one open), the
robot stands 0.6 m before it, facing it, where navigation stops before a door, and the
executive runs the one-step task ``open_door`` (no recovery: nobody is asked). From the
side the leaf swings towards, the arm pulls it; from the other, it pushes it (counted
apart). The door counts as opened only when the simulator's truth has it open and its
physics swung the leaf (``sim.door``); prints per attempt and in total: opened / tried,
simulated seconds per attempt, the robot's collisions with the leaf, and the reasons
given when not opened.
"""

from __future__ import annotations

import argparse
import collections
import json
import random
import time

from homebot.app import Fidelity, RunSettings, build_run
from homebot.embodied.hands import ArmedBodyRobot
from homebot.sim import PERSON_PREFIX
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
            "swings": "towards" if room == (world.doors[door].swings_into or
                                            world.doors[door].rooms[0]) else "away",
            "reasons": [a["reason"] for a in attempts],
            "seconds": round(sim.clock.now() - began, 1),
            "wall_s": round(time.perf_counter() - wall, 1),
            "collisions": [c for c in sim.collisions if str(c["with"]).startswith("door")]}


_FLAT = """
name: shut_door_fetch
rooms:
  - {{name: hall, polygon: [[0, 0], [4, 0], [4, 3], [0, 3]]}}
  - {{name: study, polygon: [[0, 3], [4, 3], [4, 6], [0, 6]]}}
doors:
  - {{name: study door, rooms: [hall, study], position: [{door_x}, 3], width: {width},
     state: closed, opening: 90, hinge: {hinge}, swings_into: {into}}}
placements:
  - {{name: desk, category: table, room: study, center: [{desk_x}, 5.55], size: [1.2, 0.7]}}
objects:
  - {{name: cola, category: drink, placement: desk}}
people:
  - {{name: Ada, room: hall, position: [{ada_x}, 0.6], cooperative: false}}
robot:
  pose: [{robot_x}, 1.6, 1.5708]
"""


def _fetch(seed: int) -> dict[str, object]:
    """A two-room flat drawn from ``seed`` (a 0.8 or 0.9 m door somewhere along the wall,
    hinged on either side, its leaf swinging into the hall where the robot starts or into
    the study; a desk in the study; Ada in the hall, who will not open doors): fetch the
    cola from the desk to Ada. Verified only when the truth has the cola in Ada's hands."""
    rng = random.Random(seed)
    door_x = rng.uniform(1.0, 3.0)
    world = World.from_yaml_text(_FLAT.format(
        door_x=round(door_x, 2), width=rng.choice((0.8, 0.9)),
        hinge=rng.choice(("east", "west")), into=rng.choice(("hall", "study")),
        desk_x=round(rng.uniform(1.0, 3.0), 2),
        ada_x=round(rng.uniform(0.6, 3.4), 2), robot_x=round(rng.uniform(1.0, 3.0), 2)))
    run = build_run(RunSettings(world=world, seed=seed, fidelity=Fidelity.EMBODIED,
                                time_limit=300.0))
    sim = run.simulation
    began, wall = sim.clock.now(), time.perf_counter()
    report = run.run(Task((Step("navigate", {"to": "desk"}),
                           Step("find_object", {"object": "cola", "placement": "desk"}),
                           Step("pick", {"object": "cola"}),
                           Step("navigate", {"to": "Ada"}),
                           Step("give", {"person": "Ada"}))))
    attempts = [e.data for e in sim.events.events if e.kind == "robot.open_door"]
    return {"seed": seed, "door_x": round(door_x, 2),
            "hinge": world.doors["study door"].hinge,
            "swings_into": world.doors["study door"].swings_into,
            "width": world.doors["study door"].width,
            "verified": sim.object_location["cola"] == PERSON_PREFIX + "Ada",
            "reported": report.success, "reason": report.reason,
            "door_attempts": [(a["opened"], a["reason"], a["seconds"]) for a in attempts],
            "seconds": round(sim.clock.now() - began, 1),
            "wall_s": round(time.perf_counter() - wall, 1),
            "collisions": len(sim.collisions)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("worlds", nargs="*")
    parser.add_argument("--seeds", type=int, nargs="+", default=[11])
    parser.add_argument("--fetch", action="store_true",
                        help="a whole fetch through a shut door nobody will open, per seed")
    args = parser.parse_args()
    if args.fetch:
        runs = []
        for seed in args.seeds:
            result = _fetch(seed)
            print(json.dumps(result), flush=True)
            runs.append(result)
        print(json.dumps({"seeds": args.seeds, "runs": len(runs),
                          "verified": sum(bool(r["verified"]) for r in runs),
                          "doors_opened_by_arm": sum(bool(a[0]) for r in runs
                                                     for a in r["door_attempts"]),
                          "door_attempts": sum(len(r["door_attempts"]) for r in runs)}))
        return
    results = []
    for name in args.worlds or shipped_world_names():
        world = World.load(name)
        for door, model in sorted(world.doors.items()):
            if model.width > _WIDEST:
                continue
            for room in model.rooms:
                for seed in args.seeds:
                    result = {"world": world.name, **_attempt(world, door, room, seed)}
                    print(json.dumps(result), flush=True)
                    results.append(result)
    opened = [r for r in results if r["opened"]]
    reasons = collections.Counter(str(reason) for r in results if not r["opened"]
                                  for reason in r["reasons"][:1])
    print(json.dumps({
        "seeds": args.seeds, "tried": len(results), "opened": len(opened),
        **{f"opened_{way}": f"{sum(bool(r['opened']) for r in results if r['swings'] == way)}"
                            f"/{sum(r['swings'] == way for r in results)}"
           for way in ("towards", "away")},
        "mean_seconds_opened": round(sum(float(r["seconds"]) for r in opened) /
                                     len(opened), 1) if opened else None,
        "mean_seconds_tried": round(sum(float(r["seconds"]) for r in results) /
                                    max(len(results), 1), 1),
        "collisions": sum(len(r["collisions"]) for r in results),  # type: ignore[arg-type]
        "not_opened_because": dict(reasons),
        "wall_s": round(sum(float(r["wall_s"]) for r in results), 1)}))


if __name__ == "__main__":
    main()
