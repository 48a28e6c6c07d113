"""What ``run-task`` and ``do`` share: options for a simulated run, the skill under way
(``showing_steps``), and how a run ends."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from datetime import datetime
from pathlib import Path

from rich.console import Console

from homebot.app import Run, RunSettings, build_run, disturbed
from homebot.cli.options import (
    add_fidelity_option,
    add_retry_option,
    add_time_limit_option,
    add_world_options,
    disturbance_level,
    retry_budgets,
    walker_count,
)
from homebot.cli.world import remember_last_run
from homebot.clock import DEFAULT_START, start_time
from homebot.errors import TaskError
from homebot.events import Event, EventLog
from homebot.executive import RunReport, print_report
from homebot.progress import Task, task
from homebot.world import World

__all__ = [
    "add_run_options",
    "finish_run",
    "keep_events",
    "naming_skills",
    "run_settings",
    "showing_steps",
    "simulated_run",
    "write_events",
]


def add_run_options(parser: argparse.ArgumentParser, *,
                    time_limit: float | None = None) -> None:
    """World, seed, retries, time limit, disturbances, interactive people, events and JSON.

    ``time_limit`` is ``--time-limit``'s default in simulated seconds (None: no limit).
    """
    add_world_options(parser)
    add_retry_option(parser)
    add_time_limit_option(parser, time_limit)
    parser.add_argument("--disturb", type=disturbance_level, default=0.0, metavar="LEVEL",
                        help="switch disturbances on (1 = the benchmark's level)")
    parser.add_argument("--interactive", action="store_true",
                        help="type the answers of the people the robot talks to")
    parser.add_argument("--events", type=Path, help="write the event log here (JSON lines)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    add_fidelity_option(parser)
    parser.add_argument("--walkers", type=walker_count, default=0, metavar="N",
                        help="embodied: how many people walk about on their own (default 0)")
    parser.add_argument("--start", type=_start, default=DEFAULT_START, metavar="WHEN",
                        help="the date and time the run starts at, as YYYY-MM-DD HH:MM "
                             "(default: Monday 2026-01-05 09:00)")


def _start(text: str) -> datetime:
    try:
        return start_time(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def run_settings(args: argparse.Namespace, world: World, *,
                 monitoring: bool = True) -> RunSettings:
    """The settings of the simulated home the options of ``add_run_options`` ask for."""
    return RunSettings(
        world=world, seed=args.seed,
        disturbances=disturbed(args.disturb) if args.disturb else None,
        monitoring=monitoring, fidelity=args.fidelity, walkers=args.walkers,
        interactive=args.interactive, retries=retry_budgets(args.retries),
        time_limit=args.time_limit, start=args.start)


def simulated_run(args: argparse.Namespace, world: World, *, monitoring: bool = True) -> Run:
    """The simulated home the options of ``add_run_options`` ask for."""
    return build_run(run_settings(args, world, monitoring=monitoring))


@contextmanager
def showing_steps(run: Run) -> Iterator[None]:
    """While the ``with`` block runs a task in ``run``, progress names the skill under way
    (an embodied step takes tens of seconds; the report comes at the end)."""
    with task("carrying out the task") as under_way:
        show = naming_skills(under_way, "carrying out the task")
        run.events.listeners.append(show)
        try:
            yield
        finally:
            run.events.listeners.remove(show)


def naming_skills(under_way: Task, doing: str) -> Callable[[Event], None]:
    """An event listener that describes ``under_way`` as ``doing: skill(arguments)`` each
    time a skill starts."""
    def show(event: Event) -> None:
        if event.kind == "skill.start":
            arguments = ", ".join(f"{name}={value}" for name, value in event.data["args"].items())
            under_way.describe(f"{doing}: {event.data['skill']}({arguments})")
    return show


def keep_events(args: argparse.Namespace, run: Run) -> None:
    """Remember the run for ``world show`` and write ``--events`` if asked."""
    run.record_final_state()
    remember_last_run(run.events)
    if args.events:
        write_events(run.events, args.events)


def finish_run(args: argparse.Namespace, run: Run, report: RunReport[None]) -> int:
    """Keep the events, print the report (or its JSON); 0 when the task succeeded, else 1."""
    keep_events(args, run)
    if args.json:
        print(json.dumps(report.to_dict(), ensure_ascii=False))
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
