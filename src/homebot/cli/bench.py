"""``homebot bench NAME``: run a benchmark and print its figures (``all`` runs every one)."""

from __future__ import annotations

import argparse
import importlib
import json
import pkgutil
from typing import Any

from rich.console import Console

import homebot.bench
from homebot.errors import HomebotError

__all__ = ["benchmark_names", "register"]

# Helper modules of homebot.bench that are not benchmarks themselves.
_NOT_BENCHMARKS = {"fetch_tasks"}


def benchmark_names() -> list[str]:
    """Every benchmark module in ``homebot.bench``."""
    return sorted(module.name for module in pkgutil.iter_modules(homebot.bench.__path__)
                  if module.name not in _NOT_BENCHMARKS)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("bench", help="run benchmarks and print their figures")
    bench_parsers = parser.add_subparsers(dest="benchmark", metavar="NAME")
    for name in benchmark_names():
        module = importlib.import_module(f"homebot.bench.{name}")
        sub = bench_parsers.add_parser(name, help=(module.__doc__ or "").strip().splitlines()[0])
        module.add_arguments(sub)
        sub.add_argument("--json", action="store_true", help="print the figures as JSON")
        sub.set_defaults(handler=_runner(name))
    every = bench_parsers.add_parser("all", help="every benchmark with its default settings")
    every.add_argument("--json", action="store_true")
    every.set_defaults(handler=_run_all)
    parser.set_defaults(handler=lambda args: _missing(parser))


def _missing(parser: argparse.ArgumentParser) -> int:
    raise HomebotError(f"name a benchmark: {', '.join([*benchmark_names(), 'all'])}")


def _runner(name: str) -> Any:
    def handler(args: argparse.Namespace) -> int:
        module = importlib.import_module(f"homebot.bench.{name}")
        console = None if args.json else Console()
        figures = module.run(args, console)
        if args.json:
            print(json.dumps(figures))
        return 0
    return handler


def _run_all(args: argparse.Namespace) -> int:
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
        print(json.dumps(everything))
    return 0
