"""GPSR parsing: median time per command on the shared 1000 commands (or generated ones)."""

from __future__ import annotations

import argparse
import csv
import statistics
import time
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.bench.arguments import count, readable_file, seed
from homebot.errors import BenchmarkError
from homebot.language import Vocabulary, parse_command
from homebot.language.generator import generate_commands
from homebot.world import World
from homebot.world.robocup import world_from_robocup

__all__ = ["add_arguments", "run"]

_SHARED = Path(__file__).resolve().parents[4] / "shared" / "data"
# What the seeds and issue quote for other parsers (not measured here).
CAESAR_SECONDS_PER_UTTERANCE = 10.0
TARGET_MS = 2.0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--commands", type=readable_file("--commands"), default=None,
                        help="TSV of GPSR commands (command in the last column; default: "
                             "the shared competition commands when present, else generated)")
    parser.add_argument("--robocup", type=Path,
                        default=_SHARED / "robocup" / "CompetitionTemplate",
                        help="RoboCup@Home data directory the commands were made for")
    parser.add_argument("--count", type=count("--count", 1, 100_000), default=1000,
                        help="generated commands when the shared ones are absent")
    parser.add_argument("--seed", type=seed, default=0)
    parser.add_argument("--repeat", type=count("--repeat", 1, 100), default=3,
                        help="timed passes over the commands")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Time ``parse_command`` on every command; print and return the figures."""
    commands = args.commands or _SHARED / "gpsr" / "competition_template_commands.tsv"
    if args.commands is not None and not args.robocup.is_dir():
        raise BenchmarkError(f"--robocup {args.robocup}: not a directory; --commands needs "
                             "the RoboCup@Home data directory its commands were made for")
    if commands.is_file() and args.robocup.is_dir():
        world = World.from_dict(world_from_robocup(args.robocup))
        try:
            with commands.open(encoding="utf-8") as handle:
                texts = [row[-1] for row in csv.reader(handle, delimiter="\t") if row]
        except (OSError, UnicodeDecodeError) as error:
            raise BenchmarkError(f"--commands {commands}: cannot be read ({error})") from None
        if not texts:
            raise BenchmarkError(f"--commands {commands}: holds no commands; give a TSV "
                                 "with one command a line (in the last column)")
        source = str(commands.name)
    else:
        world = World.load("apartment")
        texts = [text for text, _ in generate_commands(world, args.count, seed=args.seed)]
        source = f"{len(texts)} generated commands on apartment"
    started = time.perf_counter()
    vocabulary = Vocabulary.from_world(world)
    vocabulary_ms = (time.perf_counter() - started) * 1000
    timings: list[float] = []
    understood = 0
    for _ in range(max(1, args.repeat)):
        for text in texts:
            begin = time.perf_counter()
            result = parse_command(text, vocabulary)
            timings.append((time.perf_counter() - begin) * 1000)
            understood += bool(result)
    median = statistics.median(timings)
    figures = {
        "benchmark": "parse", "source": source, "commands": len(texts),
        "vocabulary_ms": round(vocabulary_ms, 2), "median_ms": round(median, 4),
        "p95_ms": round(sorted(timings)[int(0.95 * (len(timings) - 1))], 4),
        "max_ms": round(max(timings), 4),
        "understood": round(understood / len(timings), 4),
        "target_ms": TARGET_MS,
        "speedup_vs_caesar": round(CAESAR_SECONDS_PER_UTTERANCE * 1000 / median),
    }
    if console is not None:
        console.print(f"[bold]parse[/] on {source}: median {median:.3f} ms per command "
                      f"(p95 {figures['p95_ms']} ms, max {figures['max_ms']} ms; "
                      f"target {TARGET_MS} ms); vocabulary built in {vocabulary_ms:.1f} ms; "
                      f"{figures['understood']:.1%} understood; CAESAR quotes < "
                      f"{CAESAR_SECONDS_PER_UTTERANCE:.0f} s per utterance")
    return figures
