"""``homebot run-task FILE``: run a YAML task of skill steps in the simulated home."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape

from homebot.cli.options import add_retry_option, add_world_options, load_world, retry_budgets
from homebot.cli.world import remember_last_run
from homebot.errors import TaskError
from homebot.events import EventLog
from homebot.executive import TaskReport
from homebot.executive.taskfile import load_task
from homebot.scenarios import SimulatedRun, disturbance_level, disturbed
from homebot.sim import InteractiveResponder

__all__ = ["print_report", "register", "write_events"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("run-task", help="run a YAML task of skill steps")
    parser.add_argument("file", type=Path, help="task file: a list of {skill: NAME, ARG: VALUE}")
    add_world_options(parser)
    add_retry_option(parser)
    parser.add_argument("--disturb", type=disturbance_level, default=0.0, metavar="LEVEL",
                        help="switch disturbances on (1 = the benchmark's level)")
    parser.add_argument("--no-monitoring", action="store_true",
                        help="run as a plain sequence: no monitoring, retries or recovery")
    parser.add_argument("--interactive", action="store_true",
                        help="type the answers of the people the robot talks to")
    parser.add_argument("--events", type=Path, help="write the event log here (JSON lines)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.set_defaults(handler=run_task)


def run_task(args: argparse.Namespace) -> int:
    world = load_world(args)
    task = load_task(args.file, world)
    run = SimulatedRun.create(
        world, seed=args.seed,
        disturbances=disturbed(args.disturb) if args.disturb else None,
        monitoring=not args.no_monitoring,
        responder=InteractiveResponder() if args.interactive else None,
        retries=retry_budgets(args.retries))
    report = run.run(task)
    remember_last_run(run.simulation.events)
    if args.events:
        write_events(run.simulation.events, args.events)
    if args.json:
        print(json.dumps(report.to_dict()))
    else:
        print_report(Console(), report)
    return 0 if report.success else 1


def write_events(events: EventLog, path: Path) -> None:
    """Write the event log for ``--events``; a path that cannot be written is the person's error."""
    try:
        events.write(path)
    except OSError as error:
        raise TaskError(f"{path}: cannot write the event log ({error.strerror or error}); "
                        "check that its folder exists and is writable") from None


def print_report(console: Console, report: TaskReport) -> None:
    """The steps, their outcomes, and what the robot said, for a person to read."""
    for step in report.steps:
        colour = "green" if step.status == "verified" else (
            "yellow" if step.status == "finished" else "red")
        args = escape(", ".join(f"{key}={value}" for key, value in step.args.items()))
        error = f" ({escape(step.error)})" if step.error else ""
        recovered = f" after {escape(', '.join(step.recoveries))}" if step.recoveries else ""
        console.print(f"  [{colour}]{step.status:9}[/] {step.skill}({args}){error}{recovered}",
                      highlight=False)
    for text in report.speech:
        console.print(f"  [cyan]robot:[/] {escape(text)}", highlight=False)
    verdict = "[green]success[/]" if report.success else f"[red]failed[/]: {escape(report.reason)}"
    console.print(f"  {verdict} in {report.sim_time:.1f} s simulated", highlight=False)
