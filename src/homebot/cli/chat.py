"""``homebot chat``: talk to the robot in one simulated home that persists across commands.

Also ``homebot do "COMMAND" --answer TEXT``: the same conversation with scripted replies.
"""

from __future__ import annotations

import argparse
import select
import sys
from collections.abc import Callable, Iterable
from typing import Any

from rich.console import Console
from rich.markup import escape

from homebot.app import QUESTION_COST, conversation_for
from homebot.cli.options import GPSR_TIME_LIMIT, load_world
from homebot.cli.simulated import (
    add_run_options,
    finish_run,
    keep_events,
    showing_steps,
    simulated_run,
)
from homebot.errors import LanguageError
from homebot.executive.conversation import Turn
from homebot.files import read_typed_line

__all__ = ["add_question_cost_option", "converse", "register", "show_turn"]

_QUIT = frozenset({"quit", "exit", "bye", "goodbye", "q"})


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("chat", help="talk to the robot in one persisting home")
    add_run_options(parser, time_limit=GPSR_TIME_LIMIT)
    add_question_cost_option(parser)
    parser.set_defaults(handler=chat)


def chat(args: argparse.Namespace) -> int:
    """Read commands and answers line by line until "quit" or the end of the input."""
    world = load_world(args)
    run = simulated_run(args, world)
    console = Console()
    conversation = conversation_for(run, question_cost=args.question_cost,
                                    listen=_stdin_listener() if sys.stdin.isatty() else None)
    console.print(f"  [cyan]robot:[/] Hello, I am in the {escape(world.name)}. What can I do "
                  f"for you? (quit to end)", highlight=False)
    while True:
        queued = conversation.heard_meanwhile
        line = queued.pop(0) if queued else _read("you> ")
        if line is None or line.strip().lower() in _QUIT:
            break
        if not line.strip():
            continue
        with showing_steps(run):
            turn = conversation.hear(line)
        show_turn(console, turn)
    keep_events(args, run)
    return 0


def add_question_cost_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--question-cost", type=_cost, default=QUESTION_COST, metavar="COST",
                        help="what asking back costs, where doing the right thing is worth 1 "
                             "and a wrong one costs 1 (default 0.25): an ambiguous command is "
                             "carried out on its likeliest reading when that is worth more")


def _cost(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0.0 <= value <= 10.0:
        raise argparse.ArgumentTypeError(f"a cost from 0 to 10, not '{text}'")
    return value


def _read(prompt: str) -> str | None:
    try:
        return read_typed_line(prompt, LanguageError)
    except EOFError:
        return None


def _stdin_listener() -> Callable[[], str | None]:
    """What the person typed while a task runs (checked between steps), without waiting."""
    def listen() -> str | None:
        ready, _, _ = select.select([sys.stdin], [], [], 0)
        return sys.stdin.readline().strip() if ready else None
    return listen


def show_turn(console: Console, turn: Turn) -> None:
    """The robot's words of one turn, and how it ended."""
    for text in turn.said:
        console.print(f"  [cyan]robot:[/] {escape(text)}", highlight=False)
    if turn.report is not None:
        colour = "green" if turn.status == "done" else "red"
        console.print(f"  [{colour}]{turn.status}[/] ({len(turn.report.steps)} steps, "
                      f"{turn.report.sim_time:.1f} s simulated)", highlight=False)


def converse(args: argparse.Namespace, command: str, answers: Iterable[str]) -> int:
    """``do COMMAND --answer A --answer B``: each question the robot asks is answered by the
    next scripted reply; exit 0 only when the command was carried out and succeeded."""
    world = load_world(args)
    run = simulated_run(args, world)
    conversation = conversation_for(
        run, question_cost=getattr(args, "question_cost", QUESTION_COST))
    console = Console()
    replies = list(answers)
    with showing_steps(run):
        turn = conversation.hear(command)
    while turn.status == "asked" and replies:
        if not args.json:
            show_turn(console, turn)
            console.print(f"  [magenta]answer:[/] {escape(replies[0])}", highlight=False)
        with showing_steps(run):
            turn = conversation.hear(replies.pop(0))
    if turn.report is None:
        if args.json:
            import json

            print(json.dumps({"success": False, "speech": turn.said, "steps": [],
                              "sim_time": 0.0}, ensure_ascii=False))
        else:
            show_turn(console, turn)
        keep_events(args, run)
        return 1
    if not args.json:
        for text in turn.said[len(turn.report.speech):]:
            turn.report.speech.append(text)  # relays said after the task
    return finish_run(args, run, turn.report)
