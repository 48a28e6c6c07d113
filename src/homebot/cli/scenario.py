"""``homebot scenario NAME``: run one of the seeds' demonstrations and print its summary."""

from __future__ import annotations

import argparse
import importlib
import json
import pkgutil
from typing import Any

from rich.console import Console

import homebot.scenarios.library
from homebot.errors import HomebotError

__all__ = ["register", "scenario_names"]


def scenario_names() -> list[str]:
    """Every scenario module in ``homebot.scenarios.library``."""
    return sorted(module.name for module in pkgutil.iter_modules(
        homebot.scenarios.library.__path__))


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("scenario", help="run a demonstration from the seed papers")
    scenarios = parser.add_subparsers(dest="scenario", metavar="NAME")
    for name in scenario_names():
        module = importlib.import_module(f"homebot.scenarios.library.{name}")
        sub = scenarios.add_parser(name, help=(module.__doc__ or "").strip().splitlines()[0])
        sub.add_argument("--seed", type=int, default=0, help="seed for every random choice")
        sub.add_argument("--json", action="store_true", help="print the summary as JSON")
        module.add_arguments(sub)
        sub.set_defaults(handler=_runner(name))
    parser.set_defaults(handler=lambda args: _missing())


def _missing() -> int:
    raise HomebotError(f"name a scenario: {', '.join(scenario_names())}")


def _runner(name: str) -> Any:
    def handler(args: argparse.Namespace) -> int:
        module = importlib.import_module(f"homebot.scenarios.library.{name}")
        summary = module.run(args, None if args.json else Console())
        if args.json:
            print(json.dumps(summary))
        return 0 if summary["success"] else 1
    return handler
