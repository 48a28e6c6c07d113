"""Monte Carlo localisation in the embodied apartment: tracking, global localisation, kidnapping.

Every figure is judged against the simulator's truth (``simulation.robot_pose``),
never against the filter's own belief (the drives and their referee:
``homebot.trials.localisation``):

- **tracking**: from the known start, the robot drives a seeded route of
  placements (pure pursuit of the Navigator's path, steered by the *estimate*)
  for ``--seconds`` of simulated time with three people walking; the position
  error is sampled at every 20 Hz tick. Again with half the laser's beams spurious.
- **global localisation and kidnapping**: the robot is put at a random pose and
  the filter starts uniform over the free space; the robot wanders on its laser
  alone (towards the most open direction, turning where blocked). Then it is
  carried to another random pose without its wheels knowing. Each phase lasts
  ``--phase`` seconds; the filter has converged at the first time after which its
  error stays below 20 cm to the end of the phase (so it must hold at least
  ``phase - 30`` s), and succeeds when that is within 30 s.
- **timing**: one filter update (prediction, correction with the full 271-beam
  scan, resampling when due) with 1000 particles, on whatever core this runs on
  (run under ``taskset -c 0`` for one core).
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

import numpy as np
from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import add_plot_option, count
from homebot.errors import BenchmarkError
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.progress import track
from homebot.robot import Twist
from homebot.trials.localisation import (
    CONVERGED,
    DEADLINE,
    WALKERS,
    LocalisationSetting,
    lost_and_kidnapped,
    simulated_body,
    tracking_run,
)
from homebot.world import World

__all__ = ["add_arguments", "run"]

_TICK_PERIOD = 0.05  #: seconds per tick of the tracking runs' body (SimBody's 20 Hz default)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--runs", type=count("--runs", 1, 10_000), default=50,
                        help="seeded runs per experiment")
    parser.add_argument("--seconds", type=count("--seconds", 1, 3600), default=40,
                        help="simulated seconds of driving per tracking run")
    parser.add_argument("--phase", type=count("--phase", 30, 3600), default=40,
                        help="simulated seconds per global / kidnapping phase (at least 30)")
    parser.add_argument("--only", choices=["all", "tracking", "global", "timing"], default="all",
                        help="run one experiment only")
    add_plot_option(parser, "the tracking runs' error over time")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Run the three experiments and the timing; print a table unless ``console`` is None."""
    if args.plot is not None and args.only not in ("all", "tracking"):
        raise BenchmarkError(f"--plot draws the tracking runs, which --only {args.only} leaves "
                             "out: use --only tracking (or all)")
    world = World.load("apartment")
    navigator = Navigator(world)
    setting = LocalisationSetting(world, navigator.grid, navigator)
    began = time.perf_counter()
    figures: dict[str, Any] = {}
    errors: dict[str, list[list[float]]] = {}  #: each tracking run's error at every tick
    if args.only in ("all", "tracking"):
        figures["tracking"] = _tracking(setting, args.runs, args.seconds, spurious=0.0,
                                        errors_by_run=errors.setdefault("tracking", []))
        figures["tracking, 50 % spurious"] = _tracking(
            setting, args.runs, args.seconds, spurious=0.5,
            errors_by_run=errors.setdefault("tracking, 50 % spurious", []))
    if args.only in ("all", "global"):
        figures.update(_global_and_kidnapped(setting, args.runs, args.phase))
    if args.only in ("all", "timing"):
        figures["update timing"] = _timing(setting)
    figures["wall seconds"] = round(time.perf_counter() - began, 1)
    if console is not None:
        _print(console, figures, args)
    if args.plot is not None:
        from homebot.bench.plots import localisation_figure, save

        save(localisation_figure(errors, _TICK_PERIOD), args.plot)
    return {"benchmark": "localisation", "runs": args.runs, "figures": figures,
            "parameters": {k: str(v) for k, v in setting.parameters.describe().items()}}


##########################################################################################
# Experiments
##########################################################################################


def _tracking(setting: LocalisationSetting, runs: int, seconds: int,
              spurious: float, errors_by_run: list[list[float]]) -> dict[str, Any]:
    errors: list[float] = []
    worst: list[float] = []
    distance = 0.0
    for seed in track(range(runs), f"tracking runs, {spurious:.0%} spurious"):
        run_errors, driven = tracking_run(setting, seed, seconds, spurious)
        errors_by_run.append(run_errors)
        errors.extend(run_errors)
        worst.append(max(run_errors))
        distance += driven
    return {"median_cm": _cm(float(np.median(errors))),
            "p95_cm": _cm(float(np.percentile(errors, 95))),
            "max_cm": _cm(max(worst)),
            "runs_ever_over_20cm": sum(w > CONVERGED for w in worst),
            "samples": len(errors), "driven_m_per_run": round(distance / runs, 1)}


def _global_and_kidnapped(setting: LocalisationSetting, runs: int,
                          seconds: float) -> dict[str, Any]:
    found: list[float] = []
    recovered: list[float] = []
    for seed in track(range(runs), "global localisation and kidnapping runs"):
        localised, relocalised = lost_and_kidnapped(setting, seed, seconds)
        found.append(localised)
        recovered.append(relocalised)

    def summary(times: list[float]) -> dict[str, Any]:
        within = [t for t in times if t <= DEADLINE]
        return {"converged_share": round(len(within) / len(times), 3),
                "median_s": round(statistics.median(times), 2) if times else None,
                "runs": len(times)}
    return {"global localisation": summary(found), "kidnapping": summary(recovered)}


def _timing(setting: LocalisationSetting) -> dict[str, Any]:
    simulation, body = simulated_body(setting, 0, 0.0)
    figures: dict[str, Any] = {}
    for particles in track((1000, 5000), "update timing, 1000 and 5000 particles"):
        parameters = MclParameters(min_particles=particles, max_particles=particles)
        mcl = MonteCarloLocalisation(setting.grid, np.random.default_rng(0), parameters)
        mcl.initialise(Pose(*simulation.robot_pose), 0.1, 0.1)
        wall, cpu = [], []
        for _ in range(100):
            body.command_velocity(Twist(0.0, 0.0, 1.2))  # turns enough to update every tick
            body.tick(2)
            odometry, scan = body.odometry(), body.scan()
            began, began_cpu = time.perf_counter(), time.thread_time()
            mcl.update(odometry, scan)
            cpu.append(time.thread_time() - began_cpu)
            wall.append(time.perf_counter() - began)
        figures[f"{particles} particles"] = {
            "median_ms": round(1000 * statistics.median(wall), 2),
            "p95_ms": round(1000 * float(np.percentile(wall, 95)), 2),
            "cpu_median_ms": round(1000 * statistics.median(cpu), 2),
            "beams": len(scan.ranges), "updates": mcl.updates}
    return figures


def _cm(metres: float) -> float:
    return round(100 * metres, 2)


def _print(console: Console, figures: dict[str, Any], args: argparse.Namespace) -> None:
    table = Table(title=f"MCL in the apartment: {args.runs} seeded runs, {WALKERS} people "
                        "walking, judged by the simulator's truth")
    table.add_column("experiment")
    table.add_column("figures")
    table.add_column("target")
    targets = {"tracking": "median ≤ 5 cm, p95 ≤ 15 cm",
               "tracking, 50 % spurious": "median ≤ 10 cm",
               "global localisation": "≥ 90 % within 20 cm in 30 s",
               "kidnapping": "≥ 90 % within 20 cm in 30 s",
               "update timing": "1000 particles ≤ 10 ms"}
    for name, values in figures.items():
        table.add_row(name, _lines(values), targets.get(name, ""))
    console.print(table)


def _lines(values: Any, indent: str = "") -> str:
    if not isinstance(values, dict):
        return f"{indent}{values}"
    return "\n".join(f"{indent}{key}:\n{_lines(value, indent + '  ')}" if isinstance(value, dict)
                     else f"{indent}{key}: {value}" for key, value in values.items())
