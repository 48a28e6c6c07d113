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
from homebot.scenarios.demo import DemoTask, run_demo
from homebot.world import World

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("demo", help="watch the robot do a few tasks in the apartment")
    parser.add_argument("--world", default="apartment", help="world (default: apartment)")
    parser.add_argument("--quiet", action="store_true", help="print only the final table")
    add_fidelity_option(parser)
    parser.set_defaults(handler=demo)


def demo(args: argparse.Namespace) -> int:
    console = Console()
    world = World.load(args.world)

    def narrate(event: Event) -> None:
        data = event.data
        stamp = f"[dim]{event.time:7.1f}s[/]"
        if event.kind == "skill.start":
            shown = ", ".join(f"{k}={v}" for k, v in data["args"].items())
            console.print(f"{stamp} ▶ {data['skill']}({shown})", highlight=False)
        elif event.kind == "skill.status" and data["status"] != "finished":
            colour = {"verified": "green", "retrying": "yellow"}.get(data["status"], "red")
            detail = f" — {data.get('message') or data.get('error') or ''}"
            console.print(f"{stamp}   [{colour}]{data['status']}[/]{detail}", highlight=False)
        elif event.kind == "speech":
            console.print(f"{stamp}   [cyan]robot says:[/] {data['text']}", highlight=False)
        elif event.kind in ("sim.blocked", "robot.blocked"):
            console.print(f"{stamp}   [magenta]world:[/] the way through the {data['door']} "
                          f"is blocked ({data['blocker']})", highlight=False)
        elif event.kind == "recovery":
            console.print(f"{stamp}   [yellow]recovery protocol for {data['error']}[/]")

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
