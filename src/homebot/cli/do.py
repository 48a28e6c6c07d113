"""``homebot do "COMMAND"``: understand a spoken command and carry it out in the simulated home."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape

from homebot.cli.options import add_retry_option, add_world_options, load_world, retry_budgets
from homebot.cli.run_task import print_report, write_events
from homebot.cli.world import remember_last_run
from homebot.language import Vocabulary, parse_command
from homebot.scenarios import SimulatedRun, disturbance_level, disturbed
from homebot.sim import InteractiveResponder

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("do", help="understand a command and carry it out")
    parser.add_argument("command", help='what to do, e.g. "bring me the cola from the fridge"')
    add_world_options(parser)
    add_retry_option(parser)
    parser.add_argument("--disturb", type=disturbance_level, default=0.0, metavar="LEVEL",
                        help="switch disturbances on (1 = the benchmark's level)")
    parser.add_argument("--interactive", action="store_true",
                        help="type the answers of the people the robot talks to")
    parser.add_argument("--events", type=Path, help="write the event log here (JSON lines)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.add_argument("--planner", choices=("gpsr", "htn"), default="gpsr",
                        help="gpsr: run the parsed skill steps (default); htn: make the parse's "
                             "intent an HTN goal and plan it from the robot's beliefs")
    parser.set_defaults(handler=do)


def do(args: argparse.Namespace) -> int:
    world = load_world(args)
    parsed = parse_command(args.command, Vocabulary.from_world(world))
    if not parsed:
        said = parsed.question or parsed.reason or "I did not understand."
        if args.json:
            print(json.dumps({"success": False, "parse": parsed.to_dict(), "steps": [],
                              "speech": [said], "sim_time": 0.0}))
        else:
            Console().print(f"  [cyan]robot:[/] {escape(said)}", highlight=False)
        return 1
    run = SimulatedRun.create(
        world, seed=args.seed, disturbances=disturbed(args.disturb) if args.disturb else None,
        responder=InteractiveResponder() if args.interactive else None,
        retries=retry_budgets(args.retries))
    if args.planner == "htn":
        from homebot.cli.plan import carry_out_with_htn

        status = carry_out_with_htn(args, world, run, parsed.steps)
        if status is not None:
            remember_last_run(run.simulation.events)
            if args.events:
                write_events(run.simulation.events, args.events)
            return status
    report = run.run(parsed.to_task())
    remember_last_run(run.simulation.events)
    if args.events:
        write_events(run.simulation.events, args.events)
    if args.json:
        print(json.dumps(report.to_dict()))
    else:
        print_report(Console(), report)
    return 0 if report.success else 1
