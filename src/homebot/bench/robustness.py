"""Errands under disturbances: monitoring and recovery against a plain sequence.

``--errands fetch`` runs fetch-and-deliver tasks only (``homebot.trials.fetch``);
``--errands everyday`` (the default) mixes in taking an object from a person's hand and
putting it away, and asking someone a question and telling the operator the answer
(``homebot.trials.errands``). The referee is the simulator's truth.

Each run of one errand in one mode is an ``ErrandTask``: a picklable unit that a worker
process turns into an ``ErrandOutcome`` (``run_errand_task``), so ``--workers`` and
``--cluster`` spread the runs over processes and machines (``homebot.bench.workers``). Its
seed is the benchmark's seed and the errand's index, so the figures do not depend on which
worker ran what, nor on how many there were.
"""

from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
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
from homebot.bench.workers import (
    TaskOutcome,
    WorkerOptions,
    add_worker_options,
    run_tasks,
    worker_options,
)
from homebot.events import Event
from homebot.executive import RunReport
from homebot.navigation import Navigator
from homebot.trials.errands import Errand, ErrandKind, errands
from homebot.trials.fetch import fetch_tasks
from homebot.world import World

__all__ = ["MODES", "ErrandOutcome", "ErrandRun", "ErrandTask", "ModeResult", "add_arguments",
           "compare_modes", "errand_set", "errand_tasks", "run", "run_errand", "run_errand_task",
           "world_reference"]

#: The execution modes compared: name, and whether monitoring and recovery are on.
MODES: tuple[tuple[str, bool], ...] = (("monitored + recovery", True), ("plain sequence", False))

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
    #: errands made impossible by the disturbances (the object to fetch taken out of the
    #: home), and of those, how many the robot refused without claiming success
    impossible: int = 0
    impossible_refused: int = 0
    sim_times: list[float] = field(default_factory=list)
    wall_times: list[float] = field(default_factory=list)
    #: per errand kind: [tasks, verified done]
    by_kind: dict[str, list[int]] = field(default_factory=dict)
    #: the hands in the loop, from the simulator's log: [tried, done by the truth]
    hands: dict[str, list[int]] = field(default_factory=dict)
    #: per disturbance that struck a task (the simulator's log; "none"): [tasks, verified]
    by_disturbance: dict[str, list[int]] = field(default_factory=dict)
    #: tasks that gave no outcome (they raised, or killed their workers twice): why
    errors: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        errors = {"task_errors": self.errors} if self.errors else {}
        return errors | {
            "mode": self.mode, "tasks": self.tasks, "delivered": self.delivered,
            "verified_delivery_rate": round(self.verified / max(self.tasks, 1), 4),
            "impossible": self.impossible, "impossible_refused": self.impossible_refused,
            "verified_of_possible_rate": round(
                self.verified / max(self.tasks - self.impossible, 1), 4),
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

    def add(self, outcome: ErrandOutcome) -> None:
        """Count one errand's outcome in."""
        self.tasks += 1
        self.wall_times.append(outcome.wall)
        self.sim_times.append(outcome.sim_time)
        self.delivered += outcome.done
        self.verified += outcome.verified
        for what, tried, done in outcome.hands:
            counts = self.hands.setdefault(what, [0, 0])
            counts[0] += tried
            counts[1] += done
        counts = self.by_kind.setdefault(outcome.kind, [0, 0])
        counts[0] += 1
        counts[1] += outcome.verified
        for what in outcome.struck or ("none",):
            tally = self.by_disturbance.setdefault(what, [0, 0])
            tally[0] += 1
            tally[1] += outcome.verified
        if outcome.impossible:
            self.impossible += 1
            self.impossible_refused += not outcome.success
        if not outcome.success:
            self.failed += 1
            self.told_why += outcome.told_why


def _hands(events: list[Event]) -> tuple[tuple[str, int, int], ...]:
    """Grasps, hand-overs and receptions the embodied robot tried (its own log) and what
    the truth made of them (the simulator's log): a grasp lifted the object, a hand-over
    left it with a person, a person let go of what they put in the hand."""
    kinds = [(event.kind, event.data) for event in events]
    return (
        # a pick that never closed the hand (out of reach, or every grasp found had failed
        # before) is no grasp
        ("grasp", sum(k == "robot.pick" and d.get("outcome") not in _HAND_NOT_CLOSED
                      for k, d in kinds),
         sum(k == "sim.arm" and d.get("what") == "lifted" for k, d in kinds)),
        ("hand_over", sum(k == "robot.hand_over" for k, _ in kinds),
         sum(k == "sim.person" and d.get("did") == "took" for k, d in kinds)),
        ("receive", sum(k == "robot.receive" for k, _ in kinds),
         sum(k == "sim.person" and d.get("did") == "let go" for k, d in kinds)),
    )


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

    @property
    def impossible(self) -> bool:
        """The object to fetch was taken out of the home before the run began: no robot
        could deliver it, and the right outcome is to say so."""
        return self.errand.kind is ErrandKind.FETCH and any(
            event.kind == "sim.disturbance" and event.data.get("what") == "object_missing"
            and event.data.get("object") == self.errand.obj for event in self.events)

    def outcome(self, *, hands: bool = False) -> ErrandOutcome:
        """What the figures need of this run (with ``hands``: the hands in the loop)."""
        report = self.report
        struck = {str(event.data.get("what")) for event in self.events
                  if event.kind == "sim.disturbance"}
        return ErrandOutcome(
            kind=str(self.errand.kind), done=self.done, success=report.success,
            sim_time=report.sim_time, wall=self.wall, struck=tuple(sorted(struck)),
            told_why=any(text.startswith("I am sorry") for text in report.speech),
            impossible=self.impossible, hands=_hands(self.events) if hands else ())


@dataclass(frozen=True)
class ErrandOutcome:
    """One errand run as the figures count it: small and picklable, sent back by a worker."""

    kind: str  #: the errand's kind (``ErrandKind``)
    done: bool  #: by the truth
    success: bool  #: the robot's own report
    sim_time: float  #: simulated seconds the run took
    wall: float  #: seconds of wall time (a timing: differs from run to run)
    struck: tuple[str, ...]  #: the disturbances that struck it, sorted (the simulator's log)
    told_why: bool  #: a failure the robot explained ("I am sorry ...")
    impossible: bool = False  #: the object to fetch was gone before the run (``ErrandRun``)
    hands: tuple[tuple[str, int, int], ...] = ()  #: (what, tried, done by the truth)

    @property
    def verified(self) -> bool:
        """Done by the truth and reported done by the robot."""
        return self.done and self.success


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


def world_reference(path_or_name: str | Path) -> str:
    """How a worker finds a world: a file by its absolute path, a shipped world by name (a
    worker on another machine has the same shipped worlds, wherever it installed them)."""
    candidate = Path(path_or_name)
    if candidate.suffix or candidate.exists():
        return str(candidate.resolve())
    return str(path_or_name)


@dataclass(frozen=True)
class ErrandTask:
    """One errand of a seeded set, run in one mode: the unit a worker runs."""

    world: str  #: ``world_reference`` of the world
    mix: str  #: ``fetch`` or ``everyday`` (``errand_set``)
    tasks: int  #: the size of the seeded set the errand is drawn from
    seed: int  #: the benchmark's seed
    index: int  #: the errand's place in the set
    level: float = 1.0  #: the disturbance level
    monitoring: bool = True  #: monitoring and recovery on, or a plain sequence
    fidelity: Fidelity = Fidelity.SYMBOLIC

    @property
    def run_seed(self) -> int:
        """The run's seed: from the benchmark's seed and the task's index alone."""
        return self.seed * 100_003 + self.index


def errand_tasks(world: str, tasks: int, seed: int, level: float = 1.0,
                 fidelity: Fidelity = Fidelity.SYMBOLIC, mix: str = "everyday"
                 ) -> list[ErrandTask]:
    """Every errand of the set in every mode (``MODES``), mode by mode."""
    return [ErrandTask(world, mix, tasks, seed, index, level, monitoring, fidelity)
            for _, monitoring in MODES for index in range(tasks)]


@lru_cache(maxsize=8)
def _arena(world: str, tasks: int, seed: int, mix: str
           ) -> tuple[World, Navigator, list[Errand]]:
    """A worker's world, navigator and errand set, made once per process and set."""
    loaded = _WORLDS.get(world) or World.load(world)
    return loaded, Navigator(loaded), errand_set(loaded, tasks, seed, mix)


#: Worlds already loaded in this process, by ``world_reference``: a caller's own ``World``
#: is used as it is when its tasks run here.
_WORLDS: dict[str, World] = {}


def run_errand_task(unit: ErrandTask) -> ErrandOutcome:
    """Run one errand task (in whichever process it was sent to) and referee it."""
    world, navigator, errand_list = _arena(unit.world, unit.tasks, unit.seed, unit.mix)
    ran = run_errand(world, errand_list[unit.index], unit.run_seed, level=unit.level,
                     monitoring=unit.monitoring, navigator=navigator, fidelity=unit.fidelity)
    return ran.outcome(hands=unit.fidelity is Fidelity.EMBODIED)


def mode_results(units: list[ErrandTask], outcomes: list[TaskOutcome[ErrandOutcome]]
                 ) -> list[ModeResult]:
    """The modes' figures from the outcomes of ``units`` (in the units' order)."""
    results = {monitoring: ModeResult(mode) for mode, monitoring in MODES}
    for unit, outcome in zip(units, outcomes, strict=True):
        result = results[unit.monitoring]
        if outcome.value is None:
            result.errors.append(f"task {unit.index}: {outcome.error}")
        else:
            result.add(outcome.value)
    return [results[monitoring] for _, monitoring in MODES]


def compare_modes(world: World | str, tasks: int, seed: int, level: float = 1.0,
                  fidelity: Fidelity = Fidelity.SYMBOLIC, mix: str = "everyday",
                  workers: WorkerOptions | None = None) -> list[ModeResult]:
    """Run the same seeded errands with monitoring and recovery, and as a plain sequence
    (on ``workers``: by default one after another in this process)."""
    if isinstance(world, World):
        reference = world_reference(world.source)
        _WORLDS[reference] = world
    else:
        reference = world_reference(world)
    units = errand_tasks(reference, tasks, seed, level, fidelity, mix)
    outcomes = run_tasks(run_errand_task, units, workers or WorkerOptions(),
                         "errands, both modes")
    return mode_results(units, outcomes)


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
    add_worker_options(parser)
    add_plot_option(parser, "each mode's verified deliveries by the disturbance that struck")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Compare the modes and print a table; returns the figures."""
    world = World.load(args.world)  # a bad world is refused before any worker starts
    _WORLDS[world_reference(args.world)] = world
    results = [result.to_dict() for result in compare_modes(
        world_reference(args.world), args.tasks, args.seed, args.level, args.fidelity,
        args.errands, worker_options(args))]
    if console is not None:
        table = Table(title=f"Errands ({args.errands}), {args.tasks} tasks, disturbances "
                            f"x{args.level}, {args.fidelity} robot")
        for column in ("mode", "verified delivery", "of the possible", "impossible, refused",
                       "delivered", "failed", "told why", "median sim time",
                       "median wall time"):
            table.add_column(column)
        for result in results:
            table.add_row(result["mode"], f"{100 * result['verified_delivery_rate']:.1f} %",
                          f"{100 * result['verified_of_possible_rate']:.1f} %",
                          f"{result['impossible_refused']}/{result['impossible']}",
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
