"""``homebot demo``: a few tasks in the apartment with disturbances, narrated, then a table."""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.cli.options import add_fidelity_option, fidelity_of
from homebot.cli.scenario import run_builder
from homebot.cli.world import remember_last_run
from homebot.events import Event
from homebot.executive.narration import Narrator
from homebot.scenarios.demo import DemoTask, run_demo
from homebot.world import World

__all__ = ["register"]

#: what the demo narrates as it runs: the skills, the robot's words and what got in its way
_TOLD = frozenset({"skill.start", "skill.status", "speech", "sim.speech", "sim.blocked",
                   "robot.blocked", "recovery"})


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("demo", help="watch the robot do a few tasks in the apartment")
    parser.add_argument("--world", default="apartment", help="world (default: apartment)")
    parser.add_argument("--quiet", action="store_true", help="print only the final table")
    add_fidelity_option(parser)
    parser.set_defaults(handler=demo)


def demo(args: argparse.Namespace) -> int:
    console = Console()
    world = World.load(args.world)

    narrator = Narrator()

    def narrate(event: Event) -> None:
        # the console's narration, coloured; a step's "finished" is left to its outcome
        if event.kind not in _TOLD or event.data.get("status") == "finished":
            return
        line = narrator.markup(event.kind, event.data)
        if line is not None:
            console.print(f"[dim]{event.time:7.1f}s[/] {line}", highlight=False)

    def announce(task: DemoTask) -> None:
        console.rule(f"[bold]{task.title}")

    results = run_demo(world, run_builder(fidelity_of(args)), None if args.quiet else narrate,
                       None if args.quiet else announce)
    table = Table(title="homebot demo: tasks, outcomes and simulated durations")
    for column in ("task", "outcome", "recoveries", "simulated time"):
        table.add_column(column)
    for task, report, _ in results:
        recoveries = sum(len(step.recoveries) for step in report.steps)
        outcome = "[green]done[/]" if report.success else f"[red]failed[/]: {report.reason}"
        table.add_row(task.title, outcome, str(recoveries), f"{report.sim_time:.0f} s")
    console.print(table)
    results[-1][2].record_final_state()
    remember_last_run(results[-1][2].events)
    return 0
