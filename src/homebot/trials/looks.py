"""Look trials: what the embodied robot's look at a room reports of people, against the truth.

Each look is a seeded situation in a world: the robot stands at a free spot of a
room, turned at random, and 1 to 4 of the world's people stand, sit or lie about
it (lying on a bed or sofa of the room when it has one, else on the floor), each
with a gesture (none when lying) and a top of a random colour. The robot looks once
(``BodyRobot.perceive_people``: legs in the laser, bodies, arms and faces in the
head camera) from a pose estimate it was given, so the look is
judged and not the localisation. A percept matches a person within 0.5 m (one to
one, Hungarian assignment); recall, precision and the median position error; of
the matched: posture, top colour and gesture right; names right, wrong or not
given within face range (2.5 m), and never given beyond it. Simulated and CPU
seconds a look.
"""

from __future__ import annotations

import math
import statistics
import time
from typing import Any

import numpy as np

from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.perception.recognition import match_positions
from homebot.robot import Robot
from homebot.sim import Simulation
from homebot.world import Gesture, PlacementKind, Posture, World

__all__ = ["look_figures"]

_MATCH = 0.5  #: metres between a percept and the person it is of
_FACE_RANGE = 2.5  #: metres: names are judged within, must be absent beyond
_APART = 0.8  #: metres between people (and from the robot)
_TOPS = ("red", "green", "blue", "yellow", "black", "white", "orange", "purple")
_BEDS = ("bed", "sofa", "couch")


def look_figures(world: World, looks: int, seed: int, *, simulation: Simulation, robot: Robot,
                 navigator: Navigator) -> dict[str, Any]:
    """Figures over ``looks`` seeded looks in ``world``.

    ``robot`` is the embodied robot over ``simulation`` (built by the caller, with
    ``homebot.app``, from ``seed``); the trial places the people and the robot in the
    simulation and judges each look against it."""
    originals = {name: state.model for name, state in simulation.people.items()}
    rng = np.random.default_rng([seed, 1519])
    rooms = [room for room in world.rooms if _free_cells(navigator, world, room)]
    people = sorted(originals)
    counts = {"people": 0, "percepts": 0, "matched": 0, "posture": 0, "top": 0, "gesture": 0,
              "near": 0, "named_right": 0, "named_wrong": 0, "unnamed_near": 0, "far": 0,
              "named_far": 0}
    errors: list[float] = []
    sim_seconds: list[float] = []
    cpu_seconds: list[float] = []
    for _ in range(looks):
        room = rooms[int(rng.integers(len(rooms)))]
        cells = _free_cells(navigator, world, room)
        here = cells[int(rng.integers(len(cells)))]
        taken = [here]
        chosen = rng.choice(people, size=min(len(people), int(rng.integers(1, 5))),
                            replace=False)
        for name in people:  # the rest wait out of the way, in no room looked at
            if name not in chosen:
                simulation.people[name].model = originals[name]
        for name in chosen:
            posture = Posture(rng.choice([p.value for p in Posture]))
            spot = _spot(world, navigator, room, posture, taken, rng)
            if spot is None:
                continue
            taken.append(spot)
            gesture = Gesture(rng.choice([g.value for g in Gesture]))
            if posture is Posture.LYING:  # lying down, nobody gestures (sim.body_tracker)
                gesture = Gesture.NONE
            model = originals[name].model_copy(update={
                "posture": posture, "gesture": gesture,
                "clothes": [f"{rng.choice(_TOPS)} shirt"]})
            simulation.people[name].model = model
            simulation.move_person(name, spot)
        for name in people:
            if name not in chosen and simulation.people[name].room == room:
                simulation.move_person(name, _elsewhere(navigator, world, room, rng))
        pose = Pose(here[0], here[1], float(rng.uniform(-math.pi, math.pi)))
        simulation.robot_pose = (pose.x, pose.y, pose.theta)
        robot.localisation.initialise(pose, spread=0.01, angle_spread=0.01)  # type: ignore[attr-defined]
        began, began_cpu = simulation.clock.now(), time.process_time()
        seen = robot.perceive_people()
        cpu_seconds.append(time.process_time() - began_cpu)
        sim_seconds.append(simulation.clock.now() - began)
        truth = [(name, state) for name, state in sorted(simulation.people.items())
                 if state.room == room]
        counts["people"] += len(truth)
        counts["percepts"] += len(seen)
        pairs = match_positions([p.position for p in seen],
                                [state.position for _, state in truth], _MATCH)
        counts["matched"] += len(pairs)
        for percept_index, truth_index in pairs:
            percept, (name, state) = seen[percept_index], truth[truth_index]
            errors.append(math.dist(percept.position, state.position))
            counts["posture"] += percept.posture == state.posture.value
            colour = state.model.clothes[0].split()[0] if state.model.clothes else ""
            counts["top"] += bool(percept.clothes) and percept.clothes[0] == f"{colour} top"
            counts["gesture"] += percept.gesture == state.model.gesture.value
            if math.dist(state.position, pose.xy()) <= _FACE_RANGE:
                counts["near"] += 1
                counts["named_right"] += percept.name == name
                counts["named_wrong"] += percept.name not in (None, name)
                counts["unnamed_near"] += percept.name is None
            else:
                counts["far"] += 1
                counts["named_far"] += percept.name is not None

    def share(part: str, whole: str) -> float | None:
        return round(counts[part] / counts[whole], 3) if counts[whole] else None

    return {
        "world": world.name, "looks": looks, "seed": seed, **counts,
        "recall": share("matched", "people"), "precision": share("matched", "percepts"),
        "median_position_error_cm": round(statistics.median(errors) * 100, 1)
        if errors else None,
        "posture_right": share("posture", "matched"), "top_colour_right": share("top", "matched"),
        "gesture_right": share("gesture", "matched"),
        "named_right_within_2_5_m": share("named_right", "near"),
        "named_wrong_within_2_5_m": share("named_wrong", "near"),
        "median_simulated_s_a_look": round(statistics.median(sim_seconds), 2),
        "median_cpu_s_a_look": round(statistics.median(cpu_seconds), 3),
    }


def _free_cells(navigator: Navigator, world: World, room: str) -> list[tuple[float, float]]:
    """Centres of the free cells of ``room`` (for the robot's centre), every 20 cm."""
    grid = navigator.grid
    polygon = world.room_polygons[room]
    x0, y0, x1, y1 = polygon.bounds
    cells = []
    for x in np.arange(x0 + 0.1, x1, 0.2):
        for y in np.arange(y0 + 0.1, y1, 0.2):
            if world.room_at(float(x), float(y)) == room and \
                    not grid.blocked[grid.cell_of(float(x), float(y))]:
                cells.append((float(x), float(y)))
    return cells


def _spot(world: World, navigator: Navigator, room: str, posture: Posture,
          taken: list[tuple[float, float]], rng: np.random.Generator
          ) -> tuple[float, float] | None:
    """Where a person in ``posture`` goes: a bed or sofa of the room for lying, when there
    is one, else free floor ``_APART`` from everyone else."""
    if posture is Posture.LYING:
        beds = [p for p in world.placements.values() if p.room == room and
                p.model.kind is PlacementKind.FURNITURE and
                any(word in p.model.category.lower() or word in p.name for word in _BEDS)]
        if beds:
            centre = beds[int(rng.integers(len(beds)))].footprint.centroid
            if all(math.dist((centre.x, centre.y), other) >= _APART for other in taken):
                return (centre.x, centre.y)
    cells = [cell for cell in _free_cells(navigator, world, room)
             if all(math.dist(cell, other) >= _APART for other in taken)]
    return cells[int(rng.integers(len(cells)))] if cells else None


def _elsewhere(navigator: Navigator, world: World, room: str,
               rng: np.random.Generator) -> tuple[float, float]:
    """A free spot in another room."""
    others = [other for other in world.rooms if other != room]
    other = others[int(rng.integers(len(others)))]
    cells = _free_cells(navigator, world, other)
    return cells[int(rng.integers(len(cells)))]
