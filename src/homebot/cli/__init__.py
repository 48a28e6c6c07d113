"""The ``homebot`` command line: a thin shell over the public API.

Each command group lives in its own module of this package and exposes
``register(subparsers)``, which adds its sub-parser and sets ``handler`` to a
function ``(args) -> int`` returning the exit status. ``main`` turns every
``HomebotError`` into a one-line message on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from rich.console import Console
from rich.markup import escape

from homebot.errors import HomebotError

__all__ = ["COMMAND_GROUPS", "command_line_argument_parser", "main"]

# Modules of this package that register command groups, in help order.
COMMAND_GROUPS: tuple[str, ...] = (
    "demo", "do", "run_task", "parse", "scenario", "world", "bench", "kb", "plan", "sitlog",
    "golog",
)


def command_line_argument_parser() -> argparse.ArgumentParser:
    """Build the full ``homebot`` argument parser from every command group."""
    parser = argparse.ArgumentParser(
        prog="homebot",
        description="A cognitive software stack for domestic service robots.",
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    for group in COMMAND_GROUPS:
        module = importlib.import_module(f"homebot.cli.{group}")
        module.register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns (and, as a script, exits with) the status."""
    parser = command_line_argument_parser()
    args = parser.parse_args(argv)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 2
    try:
        return int(handler(args))
    except HomebotError as error:
        # Escaped, as messages quote what the person typed; soft-wrapped, so one line stays one.
        Console(stderr=True, highlight=False, soft_wrap=True).print(
            f"[bold red]error:[/] {escape(str(error))}", markup=True)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
