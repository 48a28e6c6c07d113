"""``homebot scenario NAME``: run one of the seeds' demonstrations and print its summary."""

from __future__ import annotations

import argparse
from typing import Any

import homebot.scenarios.library
from homebot.cli.modules import add_module_commands, lazy_subparsers, module_names
from homebot.errors import HomebotError

__all__ = ["register", "scenario_names"]


def scenario_names() -> list[str]:
    """Every scenario module in ``homebot.scenarios.library``."""
    return module_names(homebot.scenarios.library)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("scenario", help="run a demonstration from the seed papers")
    scenarios = lazy_subparsers(parser, dest="scenario", metavar="NAME")
    add_module_commands(scenarios, homebot.scenarios.library, scenario_names(),
                        add_common=_add_common,
                        exit_status=lambda summary: 0 if summary["success"] else 1)
    parser.set_defaults(handler=lambda args: _missing())


def _add_common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--seed", type=int, default=0, help="seed for every random choice")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")


def _missing() -> int:
    raise HomebotError(f"name a scenario: {', '.join(scenario_names())}")
