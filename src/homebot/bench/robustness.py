"""Errands under disturbances: monitoring and recovery against a plain sequence.

``--errands fetch`` runs fetch-and-deliver tasks only (``homebot.trials.fetch``);
``--errands everyday`` (the default) mixes in taking an object from a person's hand and
putting it away, and asking someone a question and telling the operator the answer
(``homebot.trials.errands``). The referee is the simulator's truth.
"""

from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import dataclass, field
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.app import Fidelity, RunSettings, build_run, disturbed
from homebot.bench.arguments import (
    add_fidelity_option,
    add_plot_option,
    count,
    disturbance_level,
    seed,
)
from homebot.events import Event
from homebot.executive import RunReport
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.trials.errands import Errand, ErrandKind, errands
from homebot.trials.fetch import fetch_tasks
from homebot.world import World

__all__ = ["ErrandRun", "ModeResult", "add_arguments", "compare_modes", "errand_set",
           "run", "run_errand"]

#: the embodied robot's pick outcomes (its ``robot.pick`` log) where the hand never closed
_HAND_NOT_CLOSED = frozenset({"unreachable", "tried_all"})


@dataclass
class ModeResult:
    """How one execution mode fared over the task set."""

    mode: str
    tasks: int = 0
    delivered: int = 0
    verified: int = 0
    told_why: int = 0
    failed: int = 0
    sim_times: list[float] = field(default_factory=list)
    wall_times: list[float] = field(default_factory=list)
    #: per errand kind: [tasks, verified done]
    by_kind: dict[str, list[int]] = field(default_factory=dict)
    #: the hands in the loop, from the simulator's log: [tried, done by the truth]
    hands: dict[str, list[int]] = field(default_factory=dict)
    #: per disturbance that struck a task (the simulator's log; "none"): [tasks, verified]
    by_disturbance: dict[str, list[int]] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "mode": self.mode, "tasks": self.tasks, "delivered": self.delivered,
            "verified_delivery_rate": round(self.verified / max(self.tasks, 1), 4),
            "delivery_rate": round(self.delivered / max(self.tasks, 1), 4),
            "failed": self.failed, "failed_and_told_why": self.told_why,
            "median_sim_time_s": round(statistics.median(self.sim_times or [0.0]), 1),
            "median_wall_ms": round(1000 * statistics.median(self.wall_times or [0.0]), 3),
            "by_kind": {kind: {"tasks": tasks, "verified": verified}
                        for kind, (tasks, verified) in sorted(self.by_kind.items())},
            "hands": {what: {"tried": tried, "done": done}
                      for what, (tried, done) in sorted(self.hands.items())},
            "by_disturbance": {what: {"tasks": tasks, "verified": verified}
                               for what, (tasks, verified) in sorted(self.by_disturbance.items())},
        }

    def add(self, errand_run: ErrandRun, *, hands: bool = False) -> None:
        """Count one errand run in (and, with ``hands``, the hands in the loop)."""
        report = errand_run.report
        self.tasks += 1
        self.wall_times.append(errand_run.wall)
        self.sim_times.append(report.sim_time)
        self.delivered += errand_run.done
        self.verified += errand_run.verified
        if hands:
            self.count_hands(errand_run.events)
        counts = self.by_kind.setdefault(str(errand_run.errand.kind), [0, 0])
        counts[0] += 1
        counts[1] += errand_run.verified
        struck = {str(event.data.get("what")) for event in errand_run.events
                  if event.kind == "sim.disturbance"}
        for what in struck or {"none"}:
            tally = self.by_disturbance.setdefault(what, [0, 0])
            tally[0] += 1
            tally[1] += errand_run.verified
        if not report.success:
            self.failed += 1
            self.told_why += any(text.startswith("I am sorry") for text in report.speech)

    def count_hands(self, events: list[Event]) -> None:
        """Grasps, hand-overs and receptions the embodied robot tried (its own log) and
        what the truth made of them (the simulator's log): a grasp lifted the object, a
        hand-over left it with a person, a person let go of what they put in the hand."""
        kinds = [(event.kind, event.data) for event in events]
        pairs = {
            # a pick that never closed the hand (out of reach, or every grasp found had
            # failed before) is no grasp
            "grasp": (sum(k == "robot.pick" and d.get("outcome") not in _HAND_NOT_CLOSED
                          for k, d in kinds),
                      sum(k == "sim.arm" and d.get("what") == "lifted" for k, d in kinds)),
            "hand_over": (sum(k == "robot.hand_over" for k, _ in kinds),
                          sum(k == "sim.person" and d.get("did") == "took" for k, d in kinds)),
            "receive": (sum(k == "robot.receive" for k, _ in kinds),
                        sum(k == "sim.person" and d.get("did") == "let go" for k, d in kinds)),
        }
        for what, (tried, done) in pairs.items():
            counts = self.hands.setdefault(what, [0, 0])
            counts[0] += tried
            counts[1] += done


def errand_set(world: World, tasks: int, seed: int, mix: str = "everyday") -> list[Errand]:
    """The seeded errands of a run: fetches only (``fetch``) or the everyday mix."""
    if mix == "fetch":
        return [Errand(ErrandKind.FETCH, fetch.task, fetch.person, fetch.obj)
                for fetch in fetch_tasks(world, tasks, seed)]
    return errands(world, tasks, seed)


@dataclass(frozen=True)
class ErrandRun:
    """One errand run: the robot's report and what the simulator's truth shows."""

    errand: Errand
    report: RunReport[Any]
    done: bool  #: by the truth (``Errand.done``)
    wall: float  #: seconds of wall time the run took
    events: list[Event]  #: the run's log, the simulator's with the robot's

    @property
    def verified(self) -> bool:
        """Done by the truth and reported done by the robot."""
        return self.done and self.report.success


def run_errand(world: World, errand: Errand, run_seed: int, *, level: float = 1.0,
               monitoring: bool = True, navigator: Navigator | None = None,
               fidelity: Fidelity = Fidelity.SYMBOLIC) -> ErrandRun:
    """Run ``errand`` in a fresh run of ``world`` (seed ``run_seed``, disturbances at
    ``level``), its arena set first, and referee it."""
    run = build_run(RunSettings(
        world=world, seed=run_seed, disturbances=disturbed(level), monitoring=monitoring,
        navigator=navigator, fidelity=fidelity))
    errand.arrange(run.simulation)
    started = time.perf_counter()
    report = run.run(errand.task)
    wall = time.perf_counter() - started
    return ErrandRun(errand, report, errand.done(run.simulation), wall,
                     run.simulation.events.events)


def compare_modes(world: World, tasks: int, seed: int, level: float = 1.0,
                  fidelity: Fidelity = Fidelity.SYMBOLIC,
                  mix: str = "everyday") -> list[ModeResult]:
    """Run the same seeded errands with monitoring and recovery, and as a plain sequence."""
    navigator = Navigator(world)
    results = []
    for mode, monitoring in (("monitored + recovery", True), ("plain sequence", False)):
        result = ModeResult(mode)
        for index, errand in enumerate(track(errand_set(world, tasks, seed, mix),
                                             f"errands, {mode}")):
            result.add(run_errand(world, errand, seed * 100_003 + index, level=level,
                                  monitoring=monitoring, navigator=navigator,
                                  fidelity=fidelity),
                       hands=fidelity is Fidelity.EMBODIED)
        results.append(result)
    return results


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--tasks", type=count("--tasks", 1, 20_000), default=200,
                        help="tasks per mode (default 200)")
    parser.add_argument("--seed", type=seed, default=1, help="seed of tasks and disturbances")
    parser.add_argument("--world", default="apartment", help="world file or shipped name")
    parser.add_argument("--level", type=disturbance_level, default=1.0,
                        help="disturbance level (1 = default)")
    parser.add_argument("--errands", choices=("everyday", "fetch"), default="everyday",
                        help="everyday: fetch, take from a person, ask and tell (the default); "
                             "fetch: fetch-and-deliver only")
    add_fidelity_option(parser)
    add_plot_option(parser, "each mode's verified deliveries by the disturbance that struck")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Compare the modes and print a table; returns the figures."""
    world = World.load(args.world)
    results = [result.to_dict() for result in compare_modes(world, args.tasks, args.seed,
                                                            args.level, args.fidelity,
                                                            args.errands)]
    if console is not None:
        table = Table(title=f"Errands ({args.errands}), {args.tasks} tasks, disturbances "
                            f"x{args.level}, {args.fidelity} robot")
        for column in ("mode", "verified delivery", "delivered", "failed", "told why",
                       "median sim time", "median wall time"):
            table.add_column(column)
        for result in results:
            table.add_row(result["mode"], f"{100 * result['verified_delivery_rate']:.1f} %",
                          str(result["delivered"]), str(result["failed"]),
                          str(result["failed_and_told_why"]),
                          f"{result['median_sim_time_s']} s", f"{result['median_wall_ms']} ms")
        console.print(table)
        for result in results:
            if result["hands"]:
                console.print(f"{result['mode']}: hands in the loop, by the truth: " + ", ".join(
                    f"{what} {counts['done']}/{counts['tried']}"
                    for what, counts in result["hands"].items()))
    if args.plot is not None:
        from homebot.bench.plots import robustness_figure, save

        save(robustness_figure(results, args.level), args.plot)
    return {"benchmark": "robustness", "errands": args.errands, "tasks": args.tasks,
            "seed": args.seed,
            "fidelity": str(args.fidelity), "modes": results}
