"""``homebot do "COMMAND"``: understand a spoken command and carry it out in the simulated home."""

from __future__ import annotations

import argparse
import json
from typing import Any

from rich.console import Console
from rich.markup import escape

from homebot.app import told
from homebot.cli.chat import add_question_cost_option
from homebot.cli.options import GPSR_TIME_LIMIT, load_world
from homebot.cli.simulated import (
    add_run_options,
    finish_run,
    keep_events,
    showing_steps,
    simulated_run,
)
from homebot.cli.voice import add_voice_options, speak_to_file, spoken_or_typed
from homebot.language import Vocabulary, parse_command

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("do", help="understand a command and carry it out")
    parser.add_argument("command", nargs="?",
                        help='what to do, e.g. "bring me the cola from the fridge"')
    add_run_options(parser, time_limit=GPSR_TIME_LIMIT)
    add_voice_options(parser)
    parser.add_argument("--planner", choices=("gpsr", "htn"), default="gpsr",
                        help="gpsr: run the parsed skill steps (default); htn: make the parse's "
                             "intent an HTN goal and plan it from the robot's beliefs")
    parser.add_argument("--answer", action="append", default=[], metavar="TEXT",
                        help="a reply to a question the robot asks back (repeatable, in order)")
    add_question_cost_option(parser)
    parser.set_defaults(handler=do)


def do(args: argparse.Namespace) -> int:
    world = load_world(args)
    command = spoken_or_typed(args, world)
    if command is None:
        return 1
    parsed = parse_command(command, Vocabulary.from_world(world),
                           readings=told(world, args.question_cost))
    if parsed.assumed and not args.json:
        Console().print(f"  [cyan]robot:[/] {escape(parsed.assumed)}", highlight=False)
    if not parsed and args.answer:
        from homebot.cli.chat import converse

        return converse(args, command, args.answer)
    if not parsed:
        said = parsed.question or parsed.reason or "I did not understand."
        speak_to_file([said], args.reply)
        if args.json:
            print(json.dumps({"success": False, "parse": parsed.to_dict(), "steps": [],
                              "speech": [said], "sim_time": 0.0}, ensure_ascii=False))
        else:
            Console().print(f"  [cyan]robot:[/] {escape(said)}", highlight=False)
        return 1
    run = simulated_run(args, world)
    if args.planner == "htn":
        from homebot.cli.plan import carry_out_with_htn

        with showing_steps(run):
            status = carry_out_with_htn(args, world, run, parsed.steps)
        if status is not None:
            keep_events(args, run)
            return status
    with showing_steps(run):
        report = run.run(parsed.to_task())
    speak_to_file(report.speech, args.reply)
    return finish_run(args, run, report)
