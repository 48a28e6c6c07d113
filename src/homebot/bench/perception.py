"""Perception: table-top objects (detection, recognition, position), people, faces, pointing.

**Objects.** ``--scenes`` generated table-top scenes (``homebot.sim.tabletop``),
each with 1 to 8 catalogue objects of ``--world`` standing on a table of random
size and height, turned at random and close enough that nearer ones hide
parts of farther ones; the robot looks from an approach pose. The pipeline
(``homebot.perception``: RANSAC support plane, Euclidean clustering, features,
random forest trained on other rendered views) is judged against the scene's
truth: a detection is right when it lies within 5 cm of a true object (one to
one, Hungarian assignment); precision, recall, category accuracy of the matched
ones, the median position error, and the time per frame (segmentation to
estimates; wall clock and the thread's CPU time; run under ``taskset -c 0``). The
time target is judged on the CPU time: on a shared core the wall clock also counts
the time spent waiting for it.

**Look** (``homebot.bench.perception_look``): people as the embodied robot's look at a
room reports them (laser, head camera, faces, skeleton tracker), against the truth.

**People, faces, pointing** come from ``homebot.perception.people``, ``faces``
and ``gestures``, and tags from ``lateration``, with the figure functions in
``homebot.bench.perception_people`` (``people_figures``, ``face_figures``,
``pointing_figures``, ``lateration_figures``); a section says "not built" while
its module is absent.
"""

from __future__ import annotations

import argparse
import importlib
import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np
from rich.console import Console

from homebot.bench.arguments import count, seed
from homebot.perception.recognition import TabletopPerception, match_positions
from homebot.scenarios.perceiving import trained_recogniser
from homebot.sim.tabletop import tabletop_scene
from homebot.world import World, object_catalogue

__all__ = ["add_arguments", "object_figures", "run"]

#: the issue's targets for the objects
TARGETS = {"precision": 0.95, "recall": 0.90, "category_accuracy": 0.90,
           "median_position_error_cm": 2.0, "cpu_ms_per_frame": 50.0}
_MATCH = 0.05  #: metres


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--scenes", type=count("--scenes", 1, 100_000), default=300,
                        help="table-top scenes (and people scenes)")
    parser.add_argument("--seed", type=seed, default=1, help="seeds the scenes and sensors")
    parser.add_argument("--world", default="apartment",
                        help="the world whose catalogue the objects come from (a shipped "
                             "name or a YAML file)")
    parser.add_argument("--gap", type=count("--gap", 0, 50), default=3,
                        help="centimetres kept between objects' footprints (the clustering "
                             "joins objects closer than 1.6 cm)")
    parser.add_argument("--partial-views", action="store_true",
                        help="objects may stand partly outside the picture")
    parser.add_argument("--looks", type=count("--looks", 1, 10_000), default=40,
                        help="looks at people by the embodied robot (the 'look' part)")
    parser.add_argument("--only", choices=["all", "objects", "people", "faces", "pointing",
                                           "lateration", "look"],
                        default="all", help="run one part only")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Every part asked for; each prints its figures."""
    figures: dict[str, Any] = {}
    parts: dict[str, Callable[[], dict[str, Any]]] = {
        "objects": lambda: object_figures(World.load(args.world), args.scenes, args.seed,
                                          gap=args.gap / 100,
                                          whole_in_view=not args.partial_views),
        "people": lambda: _other("people", "people_figures", args.seed, args.scenes),
        "faces": lambda: _other("faces", "face_figures", args.seed),
        "pointing": lambda: _other("gestures", "pointing_figures", args.seed),
        "lateration": lambda: _other("lateration", "lateration_figures", args.seed),
        "look": lambda: _look(World.load(args.world), args.looks, args.seed),
    }
    for name, part in parts.items():
        if args.only in ("all", name):
            figures[name] = part()
            if console is not None:
                console.print(f"[bold]{name}[/bold]: {figures[name]}")
    return {"benchmark": "perception", "figures": figures}


def _other(module: str, function: str, *arguments: int) -> dict[str, Any]:
    """Figures from another perception module, or "not built" while it is absent.

    The figure functions live in ``homebot.bench.perception_people`` (they generate
    scenes with ``homebot.sim``, which the perception modules never import)."""
    try:
        importlib.import_module(f"homebot.perception.{module}")
        found = importlib.import_module("homebot.bench.perception_people")
    except ModuleNotFoundError:
        return {"status": "not built"}
    make = getattr(found, function, None)
    if make is None:
        return {"status": "not built"}
    result: dict[str, Any] = make(*arguments)
    return result


def _look(world: World, looks: int, look_seed: int) -> dict[str, Any]:
    """The embodied robot's looks at people (``homebot.bench.perception_look``)."""
    from homebot.bench.perception_look import look_figures  # the embodied extra: OpenCV

    return look_figures(world, looks, look_seed)


def object_figures(world: World, scenes: int, scene_seed: int, *, gap: float = 0.03,
                   whole_in_view: bool = True) -> dict[str, Any]:
    """Detection, recognition and position figures over generated table-top scenes."""
    catalogue = object_catalogue(world)
    if not catalogue:
        return {"status": f"the world {world.name} has no objects"}
    began = time.perf_counter()
    recogniser = trained_recogniser(catalogue)  # its own views, not the scenes' seed
    training_s = time.perf_counter() - began
    perception = TabletopPerception(recogniser, np.random.default_rng([scene_seed, 7]))
    entries = list(catalogue.values())
    truths = found = matched = right_category = right_object = 0
    errors: list[float] = []
    wall: list[float] = []
    cpu: list[float] = []
    for index in range(scenes):
        rng = np.random.default_rng([scene_seed, index])
        scene = tabletop_scene(entries, int(rng.integers(1, 9)), rng, gap=gap,
                               whole_in_view=whole_in_view)
        started, started_cpu = time.perf_counter(), time.thread_time()
        estimates = perception.perceive(scene.frame)
        cpu.append(time.thread_time() - started_cpu)
        wall.append(time.perf_counter() - started)
        pairs = match_positions([e.position for e in estimates],
                                [placed.position for placed in scene.objects], _MATCH)
        truths += len(scene.objects)
        found += len(estimates)
        matched += len(pairs)
        for estimate_index, truth_index in pairs:
            estimate, truth = estimates[estimate_index], scene.objects[truth_index]
            right_category += estimate.category == truth.entry.category
            right_object += estimate.label == truth.entry.name
            errors.append(float(np.hypot(estimate.position[0] - truth.position[0],
                                         estimate.position[1] - truth.position[1])))
    figures: dict[str, Any] = {
        "world": world.name, "catalogue_objects": len(catalogue), "scenes": scenes,
        "gap_cm": round(gap * 100, 1), "whole_in_view": whole_in_view,
        "objects": truths, "detections": found,
        "precision": round(matched / max(found, 1), 4),
        "recall": round(matched / max(truths, 1), 4),
        "category_accuracy": round(right_category / max(matched, 1), 4),
        "object_accuracy": round(right_object / max(matched, 1), 4),
        "median_position_error_cm": round(100 * statistics.median(errors), 2) if errors
        else None,
        "ms_per_frame": round(1000 * statistics.median(wall), 2),
        "cpu_ms_per_frame": round(1000 * statistics.median(cpu), 2),
        "training_s": round(training_s, 1),
    }
    figures["targets_met"] = {
        name: (figures[name] is not None and (
            figures[name] <= target if name in {"median_position_error_cm", "cpu_ms_per_frame"}
            else figures[name] >= target))
        for name, target in TARGETS.items()}
    return figures
