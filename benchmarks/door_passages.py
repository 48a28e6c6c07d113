"""Embodied fetch tasks in a flat, judged by the simulator's truth, with what doors did.

    PYTHONPATH=src python benchmarks/door_passages.py benchmarks/flats/flat_twobed.yaml \
        --tasks 4 --seed 1

Per task: delivered (the truth: the person holds the object), simulated seconds used,
shuttles, open doors read shut. A *shuttle* is passing through a doorway and back through
the same doorway within ``_SHUTTLE_TRAVEL`` metres of driving (the robot's true trail):
going through and at once coming back. An *open door read shut* is a ``robot.blocked``
event for a door the truth has open at that moment, with a way through for the robot: a
leaf left barely ajar (its tip nearer the far jamb than the robot is wide) is a door to
have opened, and reading it so is right.
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import statistics

import numpy as np

from homebot.app import Fidelity, RunSettings, build_run
from homebot.embodied.doors import way_through
from homebot.sim import Simulation
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World

_SHUTTLE_TRAVEL = 2.0  #: metres: back through the same door within this is a shuttle
_TIME_LIMIT = 300.0  #: simulated seconds per task, as the issue's budget


def crossings(world: World, trail: list[tuple[float, float]]) -> list[tuple[str, int, float]]:
    """(door, side reached, metres driven so far) each time the trail crosses a doorway."""
    found: list[tuple[str, int, float]] = []
    travelled = 0.0
    for (x0, y0), (x1, y1) in itertools.pairwise(trail):
        travelled += math.dist((x0, y0), (x1, y1))
        for name, door in world.doors.items():
            bx, by = world.point_before_door(name, door.rooms[0], 1.0).xy()
            cx, cy = door.position
            nx, ny = bx - cx, by - cy
            before = (x0 - cx) * nx + (y0 - cy) * ny
            after = (x1 - cx) * nx + (y1 - cy) * ny
            if before * after >= 0 or math.dist((x1, y1), (cx, cy)) > door.width:
                continue
            found.append((name, 1 if after > 0 else -1, travelled))
    return found


def open_to_pass(sim: Simulation, door: str) -> bool:
    """The truth: ``door`` is open, and its leaf (where the world file leaves it, unless
    someone opened it wide) leaves the robot a straight way through."""
    if str(sim.door_state[door]) != "open":
        return False
    world = sim.world
    leaf = world.door_leaf(door)
    if leaf is None or door in sim.leaves_swung_back:
        return True
    model = world.doors[door]
    x, y = world.point_before_door(door, model.rooms[0], 1.0).xy()
    outline = np.asarray(leaf.exterior.segmentize(0.02).coords)
    return way_through(outline, model.position, (x - model.position[0], y - model.position[1]),
                       model.width, world.model.wall_thickness,
                       world.model.robot.radius) is not None


def shuttles(passes: list[tuple[str, int, float]]) -> int:
    """Crossings straight back through the door just passed."""
    return sum(1 for (door, side, at), (door2, side2, at2) in itertools.pairwise(passes)
               if door == door2 and side != side2 and at2 - at < _SHUTTLE_TRAVEL)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("world")
    parser.add_argument("--tasks", type=int, default=4)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    world = World.load(args.world)
    rows = []
    for index, fetch in enumerate(fetch_tasks(world, args.tasks, args.seed)):
        run = build_run(RunSettings(world=world, seed=args.seed + index,
                                    fidelity=Fidelity.EMBODIED, time_limit=_TIME_LIMIT))
        sim = run.simulation
        misread: list[str] = []
        sim.events.listeners.append(
            lambda event, sim=sim, misread=misread: misread.append(
                f"{event.data['door']}: {event.data['blocker']}")
            if event.kind == "robot.blocked" and event.data.get("door")
            and open_to_pass(sim, event.data["door"]) else None)
        start = sim.events.clock()
        report = run.run(fetch.task)
        passes = crossings(world, run.path())
        rows.append({"task": fetch.task.description, "delivered": delivered(sim, fetch),
                     "reported": bool(report.success), "time": round(sim.events.clock() - start, 1),
                     "crossings": len(passes), "shuttles": shuttles(passes),
                     "open_read_shut": misread})
        print(json.dumps(rows[-1]), flush=True)
    print(json.dumps({"world": world.name, "seed": args.seed, "tasks": len(rows),
                      "delivered": sum(row["delivered"] for row in rows),
                      "shuttles": sum(row["shuttles"] for row in rows),
                      "open_read_shut": sum(len(row["open_read_shut"]) for row in rows),
                      "median_time": statistics.median(row["time"] for row in rows)}))


if __name__ == "__main__":
    main()
