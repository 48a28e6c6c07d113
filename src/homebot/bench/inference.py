"""The inference cycle over seeded supermarkets with misplaced and missing products.

The supermarkets, their requests and the referee are ``homebot.trials.supermarket``.
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run, disturbed
from homebot.bench.arguments import count, seed
from homebot.inference import Inventory
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.trials.supermarket import RunParts, SupermarketTrial, run_world
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--worlds", type=count("--worlds", 1, 100_000), default=300,
                        help="seeded supermarkets")
    parser.add_argument("--requests", type=count("--requests", 1, 100), default=3,
                        help="client requests per world")
    parser.add_argument("--misplaced", type=float, default=0.3,
                        help="chance that the assistant put a product on a wrong shelf")
    parser.add_argument("--missing", type=float, default=0.1,
                        help="chance that a product ran out")
    parser.add_argument("--r-max", type=float, default=240.0, help="decision budget (s)")
    parser.add_argument("--seed", type=seed, default=0, help="first world's seed")
    parser.add_argument("--noise", type=float, default=0.0,
                        help="disturbance level (0: only the assistant's misplacements)")


def _mean(values: list[int]) -> float:
    return round(statistics.fmean(values), 3) if values else 0.0


def _run_parts(world: World, navigator: Navigator) -> RunParts:
    """The trial's runs, built by the app in ``world`` with one shared navigator."""
    return lambda seed, inference, responder, noise: build_run(RunSettings(
        world=world, seed=seed, navigator=navigator, inference=inference, responder=responder,
        disturbances=disturbed(noise) if noise > 0 else None))


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Figures over ``--worlds`` seeded supermarkets."""
    world = World.load("supermarket")
    kb_text = Inventory.load("supermarket").kb.to_text()
    began = time.perf_counter()
    trial = SupermarketTrial(requests=args.requests, misplaced=args.misplaced,
                             missing=args.missing, r_max=args.r_max, noise=args.noise)
    build = _run_parts(world, Navigator(world))
    results = [run_world(world, args.seed + index, trial, kb_text, build)
               for index in track(range(args.worlds), "supermarkets")]
    wall = time.perf_counter() - began
    requests = sum(r.requests for r in results)
    visits = [v for r in results for v in r.visits]
    baseline = [v for r in results for v in r.baseline_visits]
    searching = [v for r in results for v in r.search_visits]
    to_grasp = [v for r in results for v in r.visits_to_grasp]
    baseline_to_grasp = [v for r in results for v in r.baseline_to_grasp]
    figures = {
        "benchmark": "inference", "worlds": args.worlds, "requests": requests,
        "absent_requests": sum(r.absent for r in results),
        "right_outcomes": sum(r.right for r in results),
        "kb_consistent_worlds": sum(r.kb_consistent for r in results),
        "shelf_visits_until_in_hand": _mean(to_grasp),
        "baseline_shelf_visits_until_in_hand": _mean(baseline_to_grasp),
        "shelf_visits_per_request": round(statistics.fmean(visits), 3) if visits else 0.0,
        "put_back_visits_per_request": round(
            sum(r.put_back_visits for r in results) / max(1, requests), 3),
        "shelf_visits_per_request_without_put_backs": round(statistics.fmean(searching), 3)
        if searching else 0.0,
        "baseline_shelf_visits_per_request": round(statistics.fmean(baseline), 3)
        if baseline else 0.0,
        "baseline_right_outcomes": sum(r.baseline_right for r in results),
        "products_put_back_after_requests": sum(r.put_back for r in results),
        "sim_seconds_per_world": round(statistics.fmean(r.sim_time for r in results), 1)
        if results else 0.0,
        "wall_ms_per_world": round(1000 * wall / max(1, args.worlds), 1),
    }
    if console is not None:
        for name, value in figures.items():
            console.print(f"{name}: {value}")
    return figures
