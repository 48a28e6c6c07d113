"""``homebot bench NAME``: run a benchmark and print its figures (``all`` runs every one)."""

from __future__ import annotations

import argparse
import importlib
import json
from typing import Any

import homebot.bench
from homebot.cli.modules import add_module_commands, lazy_subparsers, module_names
from homebot.errors import HomebotError

__all__ = ["benchmark_names", "register"]

# Helper modules of homebot.bench that are not benchmarks themselves.
_NOT_BENCHMARKS = {"arguments", "fetch_tasks", "manipulation_hri"}


def benchmark_names() -> list[str]:
    """Every benchmark module in ``homebot.bench``."""
    return module_names(homebot.bench, exclude=_NOT_BENCHMARKS)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("bench", help="run benchmarks and print their figures")
    bench_parsers = lazy_subparsers(parser, dest="benchmark", metavar="NAME")
    add_module_commands(bench_parsers, homebot.bench, benchmark_names(),
                        add_common=_add_json, exit_status=lambda figures: 0)
    every = bench_parsers.add_parser("all", help="every benchmark with its default settings")
    _add_json(every)
    every.set_defaults(handler=_run_all)
    parser.set_defaults(handler=lambda args: _missing())


def _add_json(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")


def _missing() -> int:
    raise HomebotError(f"name a benchmark: {', '.join([*benchmark_names(), 'all'])}")


def _run_all(args: argparse.Namespace) -> int:
    from rich.console import Console

    console = None if args.json else Console()
    everything = []
    for name in benchmark_names():
        module = importlib.import_module(f"homebot.bench.{name}")
        parser = argparse.ArgumentParser()
        module.add_arguments(parser)
        defaults = parser.parse_args([])
        if console is not None:
            console.rule(name)
        everything.append(module.run(defaults, console))
    if args.json:
        print(json.dumps(everything, ensure_ascii=False))
    return 0
