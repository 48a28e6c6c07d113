"""Table-top object trials: generated scenes, and the pipeline judged against their truth.

``object_figures`` renders ``scenes`` seeded table-top scenes (``homebot.sim.tabletop``),
runs the perception pipeline on each and matches its estimates to the true objects
(within 5 cm, one to one): precision, recall, category and object accuracy, the median
position error, and time per frame. ``homebot bench perception`` prints them.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from homebot.perception.recognition import Recogniser, TabletopPerception, match_positions
from homebot.sim.tabletop import tabletop_scene
from homebot.world import CatalogueEntry, World, object_catalogue

__all__ = ["TARGETS", "object_figures"]

#: the issue's targets for the objects
TARGETS = {"precision": 0.95, "recall": 0.90, "category_accuracy": 0.90,
           "median_position_error_cm": 2.0, "cpu_ms_per_frame": 50.0}
_MATCH = 0.05  #: metres


def object_figures(world: World, scenes: int, scene_seed: int, *,
                   train: Callable[[Mapping[str, CatalogueEntry]], Recogniser],
                   gap: float = 0.03, whole_in_view: bool = True) -> dict[str, Any]:
    """Detection, recognition and position figures over generated table-top scenes.

    ``train`` gives the recogniser for the world's catalogue, trained as the robot's is
    (``homebot.app.perception.trained_recogniser``: the caller's, since the app builds
    what the robot runs); its time is reported as ``training_s``."""
    catalogue = object_catalogue(world)
    if not catalogue:
        return {"status": f"the world {world.name} has no objects"}
    began = time.perf_counter()
    recogniser = train(catalogue)  # its own views, not the scenes' seed
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
