"""Shut doors' hinges perceived from the head camera, judged by the world file.

    PYTHONPATH=src python benchmarks/door_perception.py --seed 1 [worlds...]

For every door of every world (default: the shipped worlds and benchmarks/flats), shut
by the simulator, the robot stands 1.2 m before it on each side, facing it, head tilted
0.2 rad down, and runs ``perception.door_leaf.perceive_door`` on one camera frame. A door
side counts as perceived when the hinge found lies within 0.08 m of the true hinge jamb
and the handle on the latch half (a side whose room is narrower than the stand-off, a
corridor, is counted apart, not tried); prints per world and in total, with the wall seconds
per perception.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np
from shapely.geometry import Point as ShapelyPoint

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.perception.door_leaf import perceive_door
from homebot.sim import Simulation
from homebot.sim.body import SimBody
from homebot.sim.camera import door_solids
from homebot.world import DoorState, World, shipped_world_names

_STAND_OFF = 1.2  #: metres before the door
_HINGE_TOLERANCE = 0.08  #: metres


def _true_hinge(world: World, door: str) -> np.ndarray:
    leaf = door_solids(world, door)[0]  # its yaw points from the hinge to the latch
    half = world.doors[door].width / 2
    return np.array(world.doors[door].position) - half * np.array(
        [math.cos(leaf.yaw), math.sin(leaf.yaw)])


def _world_score(world: World, seed: int) -> dict[str, float]:
    body = SimBody(Simulation(world, seed=seed, navigator=Navigator(world)))
    found = tried = no_room = 0
    seconds = 0.0
    for door in sorted(world.doors):
        for state in body.sim.door_state:
            body.sim.door_state[state] = DoorState.OPEN
        body.sim.door_state[door] = DoorState.CLOSED
        hinge = _true_hinge(world, door)
        for room in world.doors[door].rooms:
            before = world.point_before_door(door, room, _STAND_OFF)
            x, y = before.xy()
            if not world.room_polygons[room].contains(ShapelyPoint(x, y)):
                no_room += 1  # the room is narrower than the stand-off (a corridor)
                continue
            cx, cy = world.doors[door].position
            heading = math.atan2(cy - y, cx - x)
            body.teleport(Pose(x, y, heading))
            body.point_head(0.0, 0.2)
            frame = body.camera()
            start = time.perf_counter()
            seen = perceive_door(frame.points()[0], np.random.default_rng(seed))
            seconds += time.perf_counter() - start
            tried += 1
            if seen is None:
                continue
            turn = np.array([[math.cos(heading), -math.sin(heading)],
                             [math.sin(heading), math.cos(heading)]])
            seen_hinge = turn @ seen.hinge + (x, y)
            handle = turn @ seen.handle[:2] + (x, y)
            on_latch_half = np.linalg.norm(handle - hinge) > world.doors[door].width / 2
            if np.linalg.norm(seen_hinge - hinge) < _HINGE_TOLERANCE and on_latch_half:
                found += 1
    return {"door_sides": tried, "hinge_found": found, "no_room_to_stand": no_room,
            "wall_s_per_perception": round(seconds / max(tried, 1), 3)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("worlds", nargs="*")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    worlds = args.worlds or [*shipped_world_names(),
                             *sorted(str(p) for p in Path("benchmarks/flats").glob("*.yaml"))]
    total = {"door_sides": 0, "hinge_found": 0}
    for name in worlds:
        score = _world_score(World.load(name), args.seed)
        print(json.dumps({"world": name, **score}))
        total["door_sides"] += int(score["door_sides"])
        total["hinge_found"] += int(score["hinge_found"])
    print(json.dumps({"total": total, "seed": args.seed}))


if __name__ == "__main__":
    main()
