"""The ``homebot`` command line: a thin shell over the public API.

Each command group lives in its own module of this package and exposes
``register(subparsers)``, which adds its sub-parser and sets ``handler`` to a
function ``(args) -> int`` returning the exit status. ``main`` turns every
``HomebotError`` into a one-line message on stderr and exit status 2.

Imports are lazy (``homebot.cli.modules.LazySubcommands``): ``homebot --help`` lists the
groups from ``COMMAND_GROUPS`` without importing their modules, and a group's module is
imported only when the command line names it. To add a command group:

1. write ``homebot/cli/NAME.py`` with ``register(subparsers)`` as above;
2. add ``"COMMAND": ("NAME", "help line")`` to ``COMMAND_GROUPS``, with the same help line
   as the module's ``add_parser`` (``tests/cli`` checks that they agree);
3. keep the module's top-level imports to what its sub-commands need.

A new flag needs nothing of this: add it in the group's ``register``. A new scenario is a
module of ``homebot.scenarios.library`` (see ``homebot.cli.modules``), imported only when
chosen; its help line is its docstring's first. A new benchmark is a module of
``homebot.bench`` with a line in its registry, ``homebot.bench.BENCHMARKS``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Callable, Sequence

from homebot import __version__
from homebot.cli.modules import LazySubcommands, lazy_subparsers
from homebot.errors import HomebotError

__all__ = ["COMMAND_GROUPS", "command_line_argument_parser", "main"]

# Command groups in help order: command -> (module of this package, help line).
COMMAND_GROUPS: dict[str, tuple[str, str]] = {
    "demo": ("demo", "watch the robot do a few tasks in the apartment"),
    "do": ("do", "understand a command and carry it out"),
    "chat": ("chat", "talk to the robot in one persisting home"),
    "run-task": ("run_task", "run a YAML task of skill steps"),
    "parse": ("parse", "turn a command into skill steps"),
    "scenario": ("scenario", "run a demonstration from the seed papers"),
    "world": ("world", "check or show a world"),
    "bench": ("bench", "run benchmarks and print their figures"),
    "kb": ("kb", "check or query a non-monotonic knowledge base"),
    "plan": ("plan", "plan a task with the HTN planner and print the task network"),
    "sitlog": ("sitlog", "run or draw a SitLog dialogue model"),
    "golog": ("golog", "check, plan and run Golog programs"),
    "listen": ("listen", "hear spoken commands and show their steps"),
    "say": ("say", "speak a text with the robot's voice into a WAV"),
    "sim": ("sim_serve", "serve the simulated robot over ROS 2"),
    "ros": ("ros_serve", "offer homebot to a ROS 2 system"),
    "serve": ("serve", "watch and command the robot in a browser"),
}


def command_line_argument_parser() -> argparse.ArgumentParser:
    """Build the full ``homebot`` argument parser from every command group."""
    parser = argparse.ArgumentParser(
        prog="homebot",
        description="A cognitive software stack for domestic service robots.",
    )
    parser.add_argument("--version", action="version", version=f"homebot {__version__}")
    subparsers = lazy_subparsers(parser, dest="command", metavar="COMMAND")
    for command, (module, text) in COMMAND_GROUPS.items():
        subparsers.add_lazy(command, text, _group_register(module))
    return parser


def _group_register(module: str) -> Callable[[LazySubcommands], None]:
    def register(subparsers: LazySubcommands) -> None:
        importlib.import_module(f"homebot.cli.{module}").register(subparsers)
    return register


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns (and, as a script, exits with) the status."""
    parser = command_line_argument_parser()
    try:
        # Inside the try: an argument type may raise a HomebotError (a bad benchmark size).
        args = parser.parse_args(argv)
        handler = getattr(args, "handler", None)
        if handler is None:
            parser.print_help()
            return 2
        from homebot.progress import progress_console, showing_progress

        # progress on stderr, when it is a terminal; none beside --json's output
        with showing_progress(progress_console(quiet=bool(getattr(args, "json", False)))):
            return int(handler(args))
    except HomebotError as error:
        from rich.console import Console
        from rich.markup import escape

        from homebot.text import MOST_LISTED, problem_listing, terminal_safe

        # Capped, as a message may list problems; one line more than a listing that is
        # capped already (its "... and N more" line).
        message = problem_listing(str(error).splitlines(), MOST_LISTED + 1)
        # Escaped (markup and control characters), as messages quote what the person typed
        # or a file held; soft-wrapped, so one line stays one.
        Console(stderr=True, highlight=False, soft_wrap=True).print(
            f"[bold red]error:[/] {escape(terminal_safe(message, lines=True))}", markup=True)
        return 2
    except BrokenPipeError:
        # The reader went away (`homebot ... | head`): stop quietly, as Unix tools do.
        # Python would complain again flushing stdout at exit, so point it at nothing.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
