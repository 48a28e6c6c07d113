"""A* timing: a 15 m path on a 5 cm grid, and planned paths across the apartment."""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

import numpy as np
from rich.console import Console

from homebot.bench.arguments import count
from homebot.navigation import Navigator, astar
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeat", type=count("--repeat", 1, 10_000), default=50,
                        help="searches per case")


def _median_ms(samples: list[float]) -> float:
    return round(1000 * statistics.median(samples), 3)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Time raw A* on open grids and ``Navigator.plan`` (uncached) in the apartment."""
    side = 400  # 20 m at 5 cm
    free = np.zeros((side, side), dtype=bool)
    free[0, :] = free[-1, :] = free[:, 0] = free[:, -1] = True
    # A wall with a gap forces a detour, as a doorway does.
    obstacle = free.copy()
    obstacle[50:350, 200] = True
    cases = {
        "open floor, straight 15 m": (free, (50, 50), (50, 350)),
        "open floor, diagonal 15 m": (free, (50, 50), (262, 262)),
        "wall with a gap, 15 m": (obstacle, (200, 50), (200, 350)),
    }
    figures: dict[str, Any] = {}
    for name, (grid, start, goal) in cases.items():
        flat = grid.ravel()
        samples, length = [], 0
        for _ in range(args.repeat):
            began = time.perf_counter()
            path = astar(flat, grid.shape, start[0] * side + start[1], goal[0] * side + goal[1])
            samples.append(time.perf_counter() - began)
            length = len(path or [])
        figures[name] = {"median_ms": _median_ms(samples), "cells": length}
    world = World.load("apartment")
    samples = []
    began_grid = time.perf_counter()
    navigator = Navigator(world)
    grid_seconds = time.perf_counter() - began_grid
    pairs = [(a, b) for a in world.placements for b in world.placements if a < b]
    lengths = []
    for a, b in pairs:
        navigator._cache.clear()  # time the search, not the cache
        began = time.perf_counter()
        plan = navigator.plan(world.placements[a].approach[:2], world.placements[b].approach[:2])
        samples.append(time.perf_counter() - began)
        lengths.append(plan.length if plan else 0.0)
    figures["apartment plan (all placement pairs)"] = {
        "median_ms": _median_ms(samples), "max_ms": round(1000 * max(samples), 3),
        "pairs": len(pairs), "longest_m": round(max(lengths), 2)}
    figures["apartment grid rasterisation"] = {"ms": round(1000 * grid_seconds, 1),
                                               "cells": int(np.prod(navigator.grid.shape))}
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}")
    return {"benchmark": "navigation", "figures": figures}
