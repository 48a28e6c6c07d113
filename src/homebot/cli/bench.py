"""``homebot bench NAME``: run a registered benchmark and print its figures (``all``: every one).

The benchmarks are those of ``homebot.bench.BENCHMARKS``, in its order; a benchmark's module
is imported only when the command line names it (or ``all`` reaches it). A benchmark whose
optional extra is missing says which extra to install, and ``all`` carries on without it.
"""

from __future__ import annotations

import argparse
import importlib
import json
import time
from collections.abc import Callable
from typing import Any

from homebot.bench import BENCHMARKS, Benchmark, benchmark_names, missing_extras
from homebot.cli.modules import LazySubcommands, lazy_subparsers
from homebot.errors import BenchmarkError, HomebotError
from homebot.progress import task, track

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("bench", help="run benchmarks and print their figures")
    bench_parsers = lazy_subparsers(parser, dest="benchmark", metavar="NAME")
    for entry in BENCHMARKS:
        bench_parsers.add_lazy(entry.name, entry.help, _register_one(entry))
    bench_parsers.add_lazy("sweep", _SWEEP_HELP, _register_sweep)
    every = bench_parsers.add_parser("all", help="every benchmark with its default settings")
    _add_json(every)
    every.set_defaults(handler=_run_all)
    parser.set_defaults(handler=lambda args: _missing())


_SWEEP_HELP = ("a grid of benchmark runs (benchmark x world x disturbance level x seed x "
               "fidelity) on many workers, as one resumable table with plots")


def _register_sweep(subparsers: LazySubcommands) -> None:
    from homebot.bench import sweep

    parser = subparsers.add_parser("sweep", help=_SWEEP_HELP, description=_SWEEP_HELP)
    _add_json(parser)
    sweep.add_arguments(parser)
    parser.set_defaults(handler=lambda args: _print(sweep.run(args, _console(args)), args))


def _add_json(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")


def _missing() -> int:
    raise HomebotError(f"name a benchmark: {', '.join([*benchmark_names(), 'all'])}")


def _missing_extras_message(entry: Benchmark, missing: list[str]) -> str:
    extras = ", ".join(f"'{extra}'" for extra in missing)
    install = ",".join(missing)
    return (f"bench {entry.name} needs the {extras} extra{'s' if len(missing) > 1 else ''}: "
            f"pip install 'homebot[{install}]'")


def _register_one(entry: Benchmark) -> Callable[[LazySubcommands], None]:
    def register(subparsers: LazySubcommands) -> None:
        sub = subparsers.add_parser(entry.name, help=entry.help, description=entry.help)
        _add_json(sub)
        missing = missing_extras(entry)
        if missing:  # its module may import the extra: say what to install instead of failing
            message = _missing_extras_message(entry, missing)
            sub.set_defaults(handler=lambda args: _refuse(message))
            return
        module = importlib.import_module(entry.module)
        module.add_arguments(sub)
        sub.set_defaults(
            handler=lambda args: _print(_run(entry, module, args, _console(args)), args))
    return register


def _run(entry: Benchmark, module: Any, args: argparse.Namespace, console: Any
         ) -> dict[str, Any]:
    with task(f"bench {entry.name}"):  # its loops show their own bars beneath
        figures: dict[str, Any] = module.run(args, console)
    return figures


def _refuse(message: str) -> int:
    raise BenchmarkError(message)


def _console(args: argparse.Namespace) -> Any:
    from rich.console import Console

    return None if args.json else Console()


def _print(figures: dict[str, Any], args: argparse.Namespace) -> int:
    if args.json:
        print(json.dumps(figures, ensure_ascii=False))
    return 0


def _run_all(args: argparse.Namespace) -> int:
    """Every registered benchmark with its defaults; one that cannot run is reported, not fatal."""
    console = _console(args)
    everything: list[dict[str, Any]] = []
    failed = False
    for entry in track(BENCHMARKS, "bench all"):
        if console is not None:
            console.rule(entry.name)
        began = time.perf_counter()
        missing = missing_extras(entry)
        if missing:
            figures: dict[str, Any] = {"benchmark": entry.name,
                                       "skipped": _missing_extras_message(entry, missing)}
        else:
            module = importlib.import_module(entry.module)
            parser = argparse.ArgumentParser(prog=f"homebot bench {entry.name}")
            module.add_arguments(parser)
            try:
                figures = _run(entry, module, parser.parse_args([]), console)
            except HomebotError as error:  # reported with the others' figures, and carried on
                failed = True
                figures = {"benchmark": entry.name, "error": str(error)}
        if console is not None and ("skipped" in figures or "error" in figures):
            console.print(figures.get("skipped") or f"error: {figures['error']}")
        if console is not None:
            seconds = time.perf_counter() - began
            console.print(f"[dim]bench {entry.name}: {seconds:.0f} s wall[/dim]")
        everything.append(figures)
    if args.json:
        print(json.dumps(everything, ensure_ascii=False))
    return 1 if failed else 0
