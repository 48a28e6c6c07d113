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

**Look** (``homebot.trials.looks``): people as the embodied robot's look at a
room reports them (laser, head camera, faces, gestures from depth bursts), against the truth.

**People, faces, pointing** come from ``homebot.perception.people``, ``faces``
and ``gestures``, and tags from ``lateration``, with the figure functions in
``homebot.trials.people`` (``people_figures``, ``face_figures``,
``pointing_figures``, ``lateration_figures``).

The scenes and their referees live in ``homebot.trials`` (``tabletop``, ``people``,
``looks``); this module picks the parts and prints their figures.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import Any

from rich.console import Console

from homebot.app.perception import trained_recogniser
from homebot.bench.arguments import count, seed
from homebot.progress import task
from homebot.trials.people import (
    face_figures,
    lateration_figures,
    people_figures,
    pointing_figures,
)
from homebot.trials.tabletop import object_figures
from homebot.world import World

__all__ = ["add_arguments", "run"]

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
                                          train=trained_recogniser, gap=args.gap / 100,
                                          whole_in_view=not args.partial_views),
        "people": lambda: people_figures(args.seed, args.scenes),
        "faces": lambda: face_figures(args.seed),
        "pointing": lambda: pointing_figures(args.seed),
        "lateration": lambda: lateration_figures(args.seed),
        "look": lambda: _look(World.load(args.world), args.looks, args.seed),
    }
    for name, part in parts.items():
        if args.only in ("all", name):
            with task(f"perception: {name}"):
                figures[name] = part()
            if console is not None:
                console.print(f"[bold]{name}[/bold]: {figures[name]}")
    return {"benchmark": "perception", "figures": figures}


def _look(world: World, looks: int, look_seed: int) -> dict[str, Any]:
    """The embodied robot's looks at people (``homebot.trials.looks``), in a run the app
    builds."""
    from homebot.app import Fidelity, RunSettings, build_run
    from homebot.navigation import Navigator
    from homebot.trials.looks import look_figures

    navigator = Navigator(world)
    run = build_run(RunSettings(world=world, seed=look_seed, navigator=navigator,
                                fidelity=Fidelity.EMBODIED))
    return look_figures(world, looks, look_seed, simulation=run.simulation, robot=run.robot,
                        navigator=navigator)
