"""Fetch and deliver in the apartment with disturbances switched on (the foundation's story)."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run, disturbed
from homebot.cli.options import add_fidelity_option, disturbance_level, fidelity_of
from homebot.scenarios.summary import report_actions, scenario_summary
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_fidelity_option(parser)
    parser.add_argument("--level", type=disturbance_level, default=1.0, help="disturbance level")


def run(args: argparse.Namespace, console: Console | None) -> dict[str, Any]:
    """One seeded fetch-and-deliver task; success is the object in the person's hands."""
    world = World.load("apartment")
    fetch = fetch_tasks(world, 1, args.seed)[0]
    simulation_run = build_run(RunSettings(
        world=world, seed=args.seed, disturbances=disturbed(args.level),
        fidelity=fidelity_of(args)))
    report = simulation_run.run(fetch.task)
    really = delivered(simulation_run.simulation, fetch)
    if console is not None:
        console.print(f"{fetch.task.description}: {'delivered' if really else 'not delivered'}"
                      f" in {report.sim_time:.0f} s simulated")
        for text in report.speech:
            console.print(f"  robot: {text}", highlight=False)
    disturbances = [event.data for event in simulation_run.simulation.events.of_kind(
        "sim.disturbance")]
    return scenario_summary("fetch", report.success and really, report_actions(report),
                            report.speech, sim_time=round(report.sim_time, 2),
                            disturbances=disturbances)
