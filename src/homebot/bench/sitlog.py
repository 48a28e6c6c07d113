"""SitLog: the Appendix A program run on Listing A6's inputs (time, situations, exact history).

The README's Appendix A figure. The inputs and the expected Listing A6 are the test
suite's (``tests/sitlog/sitlog_listings.py``); without them the run is timed but its
history is not checked. Cold: the first run in a fresh interpreter (the program loaded
and run once); warm: the median of later runs of the loaded program.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import statistics
import sys
import time
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.bench.arguments import count
from homebot.progress import track
from homebot.sitlog import (
    Interpreter,
    ScriptedPerception,
    format_term,
    load_program,
    render_globals,
    render_history,
)

__all__ = ["add_arguments", "run"]

_LISTINGS = Path(__file__).resolve().parents[3] / "tests" / "sitlog" / "sitlog_listings.py"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeat", type=count("--repeat", 1, 100_000), default=200,
                        help="timed runs after the first (default 200)")


def _listings() -> Any:
    if not _LISTINGS.is_file():
        return None
    spec = importlib.util.spec_from_file_location("homebot_sitlog_listings", _LISTINGS)
    if spec is None or spec.loader is None:
        return None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def _squeezed(text: str) -> str:
    return re.sub(r"\s+", "", text)


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Time the Appendix A session and check its history against Listing A6."""
    listings = _listings()
    inputs = listings.INPUTS if listings is not None else [
        "[day(tuesday)]", "[tuesday,'not ok']", "loop", "tuesday", "[day(monday)]",
        "[monday,ok]", "finish"]
    began = time.perf_counter()
    program = load_program("appendix_a")
    result = Interpreter(program, ScriptedPerception(inputs)).run()
    cold_ms = (time.perf_counter() - began) * 1000
    samples = []
    for _ in track(range(args.repeat), "running Appendix A"):
        began = time.perf_counter()
        Interpreter(program, ScriptedPerception(inputs)).run()
        samples.append((time.perf_counter() - began) * 1000)
    trace = result.detail
    text = (render_history(trace.history) + f"\n\nOut Arg: {format_term(trace.out_arg)}\n"
            f"Out Global Vars: {render_globals(trace.globals)}\n")
    exact = None if listings is None else _squeezed(text) == _squeezed(listings.LISTING_A6)
    situations = len(list(trace.transitions()))
    figures: dict[str, Any] = {
        "benchmark": "sitlog", "situations": situations,
        "listing_a6_exact": exact,
        "cold_ms_load_and_first_run": round(cold_ms, 3),
        "warm_median_ms": round(statistics.median(samples), 4),
    }
    if console is not None:
        check = "not checked (tests/sitlog absent)" if exact is None else (
            "exactly" if exact else "NOT exactly")
        console.print(f"[bold]sitlog[/] Appendix A on Listing A6's inputs: history as Listing "
                      f"A6 {check}; {situations} situations; {figures['warm_median_ms']} ms "
                      f"per run (median of {args.repeat}); first run with loading "
                      f"{figures['cold_ms_load_and_first_run']} ms")
    return figures
