"""Fetch and deliver in the apartment with disturbances switched on (the foundation's story)."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.scenarios.summary import report_actions, scenario_summary
from homebot.trials.fetch import delivered, fetch_tasks
from homebot.world import World

__all__ = ["SHARED_OPTIONS", "add_arguments", "run"]

SHARED_OPTIONS = (SharedOption(OptionKind.FIDELITY),
                  SharedOption(OptionKind.DISTURBANCE_LEVEL, "--level", 1.0, "disturbance level"))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """No options of its own."""


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """One seeded fetch-and-deliver task; success is the object in the person's hands."""
    world = World.load("apartment")
    fetch = fetch_tasks(world, 1, args.seed)[0]
    simulation_run = build(world, seed=args.seed, level=args.level)
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
