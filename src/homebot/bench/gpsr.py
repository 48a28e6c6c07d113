"""GPSR end to end: generated commands the world can satisfy, parsed and carried out."""

from __future__ import annotations

import argparse
import statistics
import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from rich.console import Console

from homebot.app import RunSettings, build_run, disturbed
from homebot.bench.arguments import count, disturbance_level, seed
from homebot.language import Vocabulary, parse_command
from homebot.language.generator import generate_commands
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.trials.gpsr import feasible, judge
from homebot.world import World

__all__ = ["ExecutionResult", "add_arguments", "execute_commands", "run"]


@dataclass
class ExecutionResult:
    """How generated commands fared: parsed as expected, and carried out."""

    commands: int = 0
    parsed_as_expected: int = 0
    succeeded: int = 0  # judged by the simulator's ground truth
    reported: int = 0  # the robot said it succeeded
    false_claims: int = 0  # the robot said so, the home shows otherwise
    failures: Counter[str] = field(default_factory=Counter)
    wall_times: list[float] = field(default_factory=list)


def execute_commands(world: World, count: int, seed: int, level: float = 0.0) -> ExecutionResult:
    """Generate feasible commands for ``world``, parse each and run it in a fresh home."""
    navigator = Navigator(world)
    vocabulary = Vocabulary.from_world(world)
    result = ExecutionResult()
    candidates = generate_commands(world, count * 20, seed)
    chosen = [(text, steps) for text, steps in candidates if feasible(world, steps)][:count]
    for index, (text, expected) in enumerate(track(chosen, "GPSR commands")):
        parsed = parse_command(text, vocabulary)
        result.commands += 1
        result.parsed_as_expected += [s.to_dict() for s in parsed.steps] == [
            s.to_dict() for s in expected]
        if not parsed:
            result.failures[f"parse {parsed.status}"] += 1
            continue
        simulated = build_run(RunSettings(
            world=world, seed=seed * 10_007 + index, navigator=navigator,
            disturbances=disturbed(level) if level else None))
        began = time.perf_counter()
        report = simulated.run(parsed.to_task())
        result.wall_times.append(time.perf_counter() - began)
        done, why = judge(simulated.simulation, parsed.steps, report)
        result.reported += report.success
        result.false_claims += report.success and not done
        if done:
            result.succeeded += 1
        elif report.success:
            result.failures[f"truth: {why}"] += 1
        else:
            last = report.steps[-1]
            result.failures[f"{last.skill}: {last.error}"] += 1
    return result


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--commands", type=count("--commands", 1, 100_000), default=200,
                        help="commands to carry out")
    parser.add_argument("--seed", type=seed, default=1)
    parser.add_argument("--world", default="apartment", help="world file or shipped name")
    parser.add_argument("--level", type=disturbance_level, default=0.0,
                        help="disturbance level (0: none, 1: the robustness benchmark's)")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Carry out generated commands and print how many succeeded."""
    world = World.load(args.world)
    result = execute_commands(world, args.commands, args.seed, args.level)
    figures = {
        "benchmark": "gpsr", "world": world.name, "commands": result.commands,
        "disturbance_level": args.level,
        "parsed_as_expected": result.parsed_as_expected,
        "success_rate": round(result.succeeded / max(result.commands, 1), 4),
        "judged_by": "ground truth",
        "reported_success_rate": round(result.reported / max(result.commands, 1), 4),
        "false_claims": result.false_claims,
        "failures": dict(result.failures),
        "median_wall_ms": round(1000 * statistics.median(result.wall_times or [0.0]), 3),
    }
    if console is not None:
        console.print(f"{result.succeeded}/{result.commands} generated commands carried out "
                      f"in the {world.name} ({100 * figures['success_rate']:.1f} %, judged by "
                      f"the simulator's ground truth; the robot reported {result.reported}, "
                      f"{result.false_claims} of them wrongly); "
                      f"{result.parsed_as_expected} parsed exactly as generated; "
                      f"median {figures['median_wall_ms']} ms per command")
        for reason, times in result.failures.most_common():
            console.print(f"  failed {times}×: {reason}")
    return figures
