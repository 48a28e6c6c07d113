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
from homebot.progress import track
from homebot.world import World
from homebot.world.robocup import world_from_robocup

__all__ = ["add_arguments", "run"]

_SHARED = Path(__file__).resolve().parents[4] / "shared" / "data"
# Quoted, not measured here: CAESAR's paper (seeds/caesar-domestic-service-robot.txt)
# gives < 10 s per utterance for its parser. Printed as quoted, never divided into a ratio.
CAESAR_SECONDS_PER_UTTERANCE = 10.0
TARGET_MS = 2.0
# The test suite's checker of the shared commands, written apart from the parser.
_EXPECTATIONS = Path(__file__).resolve().parents[3] / "tests" / "language" / "gpsr_expectations.py"


def _shared_expectations(robocup: Path) -> Any:
    """The expected steps of each shared command, from the independent checker (or None)."""
    if not _EXPECTATIONS.is_file():
        return None
    import importlib.util

    spec = importlib.util.spec_from_file_location("homebot_gpsr_expectations", _EXPECTATIONS)
    if spec is None or spec.loader is None:
        return None
    import sys

    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module.Expectations(module.Names.from_directory(str(robocup)))


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
                rows = [row for row in csv.reader(handle, delimiter="\t") if row]
            texts = [row[-1] for row in rows]
        except (OSError, UnicodeDecodeError) as error:
            raise BenchmarkError(f"--commands {commands}: cannot be read ({error})") from None
        if not texts:
            raise BenchmarkError(f"--commands {commands}: holds no commands; give a TSV "
                                 "with one command a line (in the last column)")
        source = str(commands.name)
        checker = _shared_expectations(args.robocup) if all(len(r) >= 5 for r in rows) else None
        expected: list[Any] | None = None
        if checker is not None:
            expected = [checker.expected(row[1], row[2], row[-1]) for row in rows]
    else:
        world = World.load("apartment")
        generated = generate_commands(world, args.count, seed=args.seed)
        texts = [text for text, _ in generated]
        expected = [[step.to_dict() for step in steps] for _, steps in generated]
        source = f"{len(texts)} generated commands on apartment"
    started = time.perf_counter()
    vocabulary = Vocabulary.from_world(world)
    vocabulary_ms = (time.perf_counter() - started) * 1000
    timings: list[float] = []
    understood = 0
    exact = 0
    for repeat in track(range(max(1, args.repeat)),
                        f"parsing {len(texts)} commands, each repeat"):
        for index, text in enumerate(texts):
            begin = time.perf_counter()
            result = parse_command(text, vocabulary)
            timings.append((time.perf_counter() - begin) * 1000)
            if repeat == 0:
                understood += bool(result)
                exact += bool(result) and expected is not None and (
                    result.to_dict()["steps"] == expected[index])
    median = statistics.median(timings)
    figures = {
        "benchmark": "parse", "source": source, "commands": len(texts),
        "vocabulary_ms": round(vocabulary_ms, 2), "median_ms": round(median, 4),
        "p95_ms": round(sorted(timings)[int(0.95 * (len(timings) - 1))], 4),
        "max_ms": round(max(timings), 4),
        "status_ok": understood,
        "exact_skill_sequences": exact if expected is not None else None,
        "target_ms": TARGET_MS,
        "caesar_seconds_per_utterance_quoted": CAESAR_SECONDS_PER_UTTERANCE,
    }
    if console is not None:
        console.print(f"[bold]parse[/] on {source}: median {median:.3f} ms per command "
                      f"(p95 {figures['p95_ms']} ms, max {figures['max_ms']} ms; "
                      f"target {TARGET_MS} ms); vocabulary built in {vocabulary_ms:.1f} ms; "
                      f"exact skill sequences: "
                      f"{'not checked' if expected is None else f'{exact}/{len(texts)}'} "
                      f"(status ok: {understood}/{len(texts)}); CAESAR's parser: < "
                      f"{CAESAR_SECONDS_PER_UTTERANCE:.0f} s per utterance (quoted from the "
                      "CAESAR paper, not measured)")
    return figures
