"""Navigation: stage-1 A* timing, and 200 goals driven through the apartment with people walking.

**Timing**: stage-1 A* for 15 m paths on a 5 cm grid (open floor, round a long
wall, and round a long wall on a grid the apartment's size): on a grid whose
jump tables are kept, on a grid seen for the first time, the tables' build
alone, and libtcod alone; and ``Navigator.plan`` between every placement pair.

**Driving** (``--goals N``): the embodied robot (``SimBody``, three people
walking) drives to N seeded goals in turn, half placement approach poses and
half random free points, each with the robot's whole navigation
(``RecoveringNavigation``: stage 1's path, a local controller, and replanning
round what the laser sees or waiting when blocked) with two local controllers:
CAESAR's stage 2 (``MotionSearchPlanner``) and the Dynamic Window Approach
baseline, each in its own simulation with the same seed and goals.
Everything is judged by the simulator's truth: collisions are
``simulation.collisions`` (walls, furniture, people); a goal is reached when
the true position ends within 0.3 m of it. When a goal was missed, the robot
is carried (truth only) to that goal before the next one, so both controllers
always face the same start and goal. Smoothness is the mean absolute angular
acceleration of the base (rad/s², from the velocity at each 20 Hz tick while
driving); also reported: mean absolute linear acceleration. Cycle times are
wall-clock per ``plan`` call on whatever core this runs on (``taskset -c 0``).
The pose the controllers steer by is ``--pose``: the truth (default, fast),
odometry anchored at each goal's start (it drifts during the goal), or Monte
Carlo localisation started near the truth at each goal (as the robot does).

**One goal alone**: ``--only-goal K`` (or ``--from K``) measures goal K (0-based, as
``missed goals`` lists them) in its own situation: the robot, the people and their
seeded schedules as the whole run left them. The goals before are driven unmeasured,
or, with ``--snapshots DIR`` (written by an earlier run with the same options and code),
the situation is read back from there. ``--trace FILE`` writes each measured goal as
a JSON line: the true pose, velocity and people at every control period, and every
stage-1 plan (None: the robot waited).

The goals, the drives and their referee are ``homebot.trials.driving``; this module times
A*, picks the options and aggregates the figures.
"""

from __future__ import annotations

import argparse
import random
import statistics
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console

from homebot.bench.arguments import add_plot_option, count, seed
from homebot.errors import BenchmarkError
from homebot.geometry import Pose
from homebot.navigation import Navigator, astar
from homebot.navigation.astar import cached_jump_tables, forget_jump_tables, libtcod_astar
from homebot.navigation.jump_points import jump_tables
from homebot.trials.driving import DriveOutcome, DrivingTrial, drive, drive_goals
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeat", type=count("--repeat", 1, 10_000), default=50,
                        help="searches per A* timing case")
    parser.add_argument("--goals", type=count("--goals", 0, 5000), default=0,
                        help="goals to drive to per controller (0: timing only; the issue's "
                             "figure is --goals 200)")
    parser.add_argument("--planner", choices=["stage2", "dwa", "both"], default="both",
                        help="which local controller drives")
    parser.add_argument("--pose", choices=["truth", "odometry", "mcl"], default="truth",
                        help="the pose the controllers steer by (mcl: Monte Carlo "
                             "localisation from the laser, as the robot does)")
    parser.add_argument("--walkers", type=count("--walkers", 0, 20), default=3,
                        help="people walking about")
    parser.add_argument("--seed", type=seed, default=1, help="seeds goals, people and sensors")
    parser.add_argument("--from", dest="first", type=count("--from", 0, 4999), default=0,
                        help="drive from this goal on (0-based, as 'per goal' lists them); the "
                             "goals before it are driven unmeasured to reach its situation "
                             "(robot, people, schedules), or read from --snapshots")
    parser.add_argument("--only-goal", type=count("--only-goal", 0, 4999), default=None,
                        help="drive this one goal alone (0-based), in its situation as --from")
    parser.add_argument("--snapshots", type=Path, default=None,
                        help="a folder: the situation at each goal's start is kept there "
                             "(goal-NNNN-PLANNER.pickle.gz), and read back by --from/--only-goal "
                             "instead of driving the goals before (same code, seed, walkers)")
    parser.add_argument("--trace", type=Path, default=None,
                        help="write what happened in each measured goal (JSON lines: the "
                             "robot's true pose, people, stops, replans) to this file")
    add_plot_option(parser, "the true paths driven and each controller's smoothness (with "
                            "--goals)")


def _median_ms(samples: list[float]) -> float:
    return round(1000 * statistics.median(samples), 3)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """A* timing, then (with ``--goals``) the driving comparison."""
    if args.plot is not None and not args.goals:
        raise BenchmarkError("--plot draws the drives: give --goals N as well")
    figures = _astar_timing(args.repeat)
    if args.goals:
        figures["driving"] = _driving(args)
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}")
    return {"benchmark": "navigation", "figures": figures}


def _astar_timing(repeat: int) -> dict[str, Any]:
    """Time stage-1 A* on 15 m cases and ``Navigator.plan`` (uncached) in the apartment.

    Per case: ``median_ms`` is ``astar`` on a grid whose jump tables are kept
    (as the Navigator's static masks'): JPS over the kept tables (or in a
    small window round start and goal, when that window is at most 1/32 of the
    grid and proves its path); ``first_search_ms`` on a grid never seen
    (``plan_around``'s new mask each call), whose tables are built first;
    ``tables_ms`` building the whole grid's jump tables alone;
    ``libtcod_ms`` the search by libtcod's A* alone, as stage 1
    ran before jump point search. Each is a median wall-clock time, and beside
    it (``*cpu_ms``) the median CPU time of the thread: on a shared, loaded
    machine the wall clock also counts the time spent waiting for the core.
    """
    side = 400  # 20 m at 5 cm
    free = np.zeros((side, side), dtype=bool)
    free[0, :] = free[-1, :] = free[:, 0] = free[:, -1] = True
    # A wall with a gap forces a detour, as a doorway does.
    obstacle = free.copy()
    obstacle[50:350, 200] = True
    # The apartment's grid size (208 x 248 cells), a wall across all but its ends.
    apartment = np.zeros((208, 248), dtype=bool)
    apartment[0, :] = apartment[-1, :] = apartment[:, 0] = apartment[:, -1] = True
    apartment[10:198, 124] = True
    cases = {
        "open floor, straight 15 m": (free, (50, 50), (50, 350)),
        "open floor, diagonal 15 m": (free, (50, 50), (262, 262)),
        "wall with a gap, 15 m": (obstacle, (200, 50), (200, 350)),
        "long wall, apartment-sized grid, 14 m": (apartment, (104, 20), (104, 228)),
    }
    figures: dict[str, Any] = {}
    for name, (grid, start, goal) in cases.items():
        figures[name] = _astar_case(grid, start, goal, repeat)
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
        plan = navigator.plan(world.placements[a].approach.xy(), world.placements[b].approach.xy())
        samples.append(time.perf_counter() - began)
        lengths.append(plan.length if plan else 0.0)
    figures["apartment plan (all placement pairs)"] = {
        "median_ms": _median_ms(samples), "max_ms": round(1000 * max(samples), 3),
        "pairs": len(pairs), "longest_m": round(max(lengths), 2)}
    mask = navigator.grid.blocked_with(frozenset())
    table_samples = []
    for _ in range(repeat):
        began = time.perf_counter()
        jump_tables(mask.ravel(), navigator.grid.shape)
        table_samples.append(time.perf_counter() - began)
    figures["apartment grid rasterisation"] = {"ms": round(1000 * grid_seconds, 1),
                                               "cells": int(np.prod(navigator.grid.shape)),
                                               "jump_tables_ms": _median_ms(table_samples)}
    return figures


def _astar_case(grid: np.ndarray, start: tuple[int, int], goal: tuple[int, int],
                repeat: int) -> dict[str, Any]:
    """One A* timing case: kept tables, a first search, the tables alone, libtcod alone."""
    flat, columns = grid.ravel(), grid.shape[1]
    origin, target = start[0] * columns + start[1], goal[0] * columns + goal[1]
    wall: dict[str, list[float]] = {"": [], "first_search_": [], "tables_": [], "libtcod_": []}
    cpu: dict[str, list[float]] = {name: [] for name in wall}
    lengths = set()

    def clock(name: str, work: Callable[[], Any]) -> Any:
        began, began_cpu = time.perf_counter(), time.thread_time()
        result = work()
        cpu[name].append(time.thread_time() - began_cpu)
        wall[name].append(time.perf_counter() - began)
        return result

    for _ in range(repeat):
        forget_jump_tables()
        path = clock("first_search_", lambda: astar(flat, grid.shape, origin, target))
        clock("tables_", lambda: jump_tables(flat, grid.shape))
        cached_jump_tables(flat, grid.shape)
        kept = clock("", lambda: astar(flat, grid.shape, origin, target))
        reference = clock("libtcod_", lambda: libtcod_astar(flat, grid.shape, origin, target))
        lengths |= {len(found or []) for found in (path, kept, reference)}
    forget_jump_tables()
    figures: dict[str, Any] = {}
    for name in wall:
        figures[f"{name or 'median_'}ms"] = _median_ms(wall[name])
        figures[f"{name}cpu_ms"] = _median_ms(cpu[name])
    figures["cells"] = sorted(lengths)
    return figures


# ---------------------------------------------------------------------- driving


def _driving(args: argparse.Namespace) -> dict[str, Any]:
    world = World.load("apartment")
    navigator = Navigator(world)
    trial = DrivingTrial(seed=args.seed, goals=args.goals, walkers=args.walkers, pose=args.pose,
                         first=args.first, only_goal=args.only_goal,
                         snapshots=args.snapshots, trace=args.trace)
    targets = drive_goals(world, navigator, args.goals, random.Random(f"goals:{args.seed}"))
    names = ["stage2", "dwa"] if args.planner == "both" else [args.planner]
    outcomes = {name: drive(name, world, navigator, targets, trial) for name in names}
    if args.plot is not None:
        _plot(args.plot, navigator, targets, outcomes)
    figures: dict[str, Any] = {
        name: outcome.summary() for name, outcome in outcomes.items()}
    figures["pose source"] = args.pose
    figures["walkers"] = args.walkers
    if len(outcomes) == 2:
        stage2, dwa = outcomes["stage2"], outcomes["dwa"]
        both = [i for i in range(len(stage2.reached)) if stage2.reached[i] and dwa.reached[i]]
        if both:
            time_stage2 = statistics.fmean(stage2.durations[i] for i in both)
            time_dwa = statistics.fmean(dwa.durations[i] for i in both)
            figures["stage2 vs dwa"] = {
                "goals reached by both": len(both),
                "mean time on them, s": [round(time_stage2, 2), round(time_dwa, 2)],
                "time ratio": round(time_stage2 / time_dwa, 3),
                "angular acceleration ratio": round(
                    stage2.summary()["mean |angular acceleration|, rad/s2"] /
                    max(dwa.summary()["mean |angular acceleration|, rad/s2"], 1e-9), 3)}
    return figures


def _plot(path: Path, navigator: Navigator, targets: list[Pose],
          outcomes: dict[str, DriveOutcome]) -> None:
    from homebot.bench.plots import navigation_figure, save

    grid = navigator.grid
    rows, columns = grid.shape
    extent = (grid.origin[0], grid.origin[1], grid.origin[0] + columns * grid.resolution,
              grid.origin[1] + rows * grid.resolution)
    first = min(outcome.first_goal for outcome in outcomes.values())
    measured = targets[first:first + max(len(o.paths) for o in outcomes.values())]
    save(navigation_figure(grid.occupied, extent, [goal.xy() for goal in measured],
                           {name: outcome.paths for name, outcome in outcomes.items()},
                           {name: outcome.angular for name, outcome in outcomes.items()},
                           first), path)
