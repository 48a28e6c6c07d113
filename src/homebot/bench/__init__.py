"""Benchmarks run by ``homebot bench NAME``, listed in one explicit registry.

Each benchmark is a module of this package with ``add_arguments(parser)`` and
``run(args, console) -> dict`` (the figures; ``console`` is None under ``--json``). It times,
loops, aggregates and prints; the episodes it runs and the referees that judge them against
the simulator's truth are product code in ``homebot.trials``.

To add a benchmark, write its module and add one ``Benchmark`` line to ``BENCHMARKS``: the
order there is the order of ``homebot bench --help`` and of ``homebot bench all``. The
registry is read without importing any benchmark, so ``homebot bench --help`` stays light.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass

from homebot.errors import BenchmarkError

__all__ = ["BENCHMARKS", "EXTRA_MODULES", "Benchmark", "benchmark", "benchmark_names",
           "missing_extras"]

#: The libraries whose absence means an optional extra is not installed (pyproject's extras).
EXTRA_MODULES: dict[str, tuple[str, ...]] = {
    "embodied": ("cv2", "sklearn", "mujoco", "numba"),
    "speech": ("pocketsphinx", "espeakng_loader", "jiwer"),
    "ros": ("cyclonedds", "rosbags"),
    "web": ("fastapi", "uvicorn"),
    "cluster": ("distributed",),
}


@dataclass(frozen=True)
class Benchmark:
    """One registered benchmark: its command name, module, help line and the extras it needs."""

    name: str
    module: str
    help: str
    extras: tuple[str, ...] = ()


def _bench(name: str, help: str, *extras: str) -> Benchmark:
    return Benchmark(name, f"homebot.bench.{name}", help, extras)


#: Every benchmark, in the order ``homebot bench all`` runs them (fast ones first).
BENCHMARKS: tuple[Benchmark, ...] = (
    _bench("parse", "GPSR parsing: median time per command on the shared 1000 commands "
           "(or generated ones)"),
    _bench("kb", "knowledge base: load time, services on 10 000 individuals, chained defaults, "
           "updates"),
    _bench("kb_original", "KB fidelity: our answers beside SitLog's own KB service under "
           "SWI-Prolog, on one KB"),
    _bench("sitlog", "SitLog: the Appendix A program run on Listing A6's inputs (time, "
           "situations, exact history)"),
    _bench("golog", "Golog solve: Order Cups at horizon 4 and the maze at horizon 8 (nodes per "
           "second, time)"),
    _bench("maintenance", "self-maintenance: RIPS with crashing components (completion, "
           "repairs, violations) and speed"),
    _bench("referring", "referring expressions on generated table tops: right object, or a "
           "question when it is close"),
    _bench("htn", "HTN planning speed: our planner beside GTPyhop on the bring-object domain, "
           "and tidy-up scaling"),
    _bench("inference", "the inference cycle over seeded supermarkets with misplaced and "
           "missing products"),
    _bench("gpsr", "GPSR end to end: generated commands the world can satisfy, parsed and "
           "carried out"),
    _bench("robustness", "everyday errands (fetch, take, ask) under disturbances: monitoring "
           "and recovery against a plain sequence"),
    _bench("fetch", "wall time of one simulated fetch-and-deliver task, cold (every cache "
           "cleared) and warm"),
    _bench("startup", "one-shot commands (parse, kb query, --help) in fresh processes: wall and "
           "CPU from start to exit, beside a bare Python start"),
    _bench("long_run", "a long-running simulation: memory over thousands of consecutive tasks "
           "in one home"),
    _bench("navigation", "navigation: stage-1 A* timing, and goals driven through the "
           "apartment with people walking", "embodied"),
    _bench("follow", "Follow Me: the operator walks 15-25 m with two people crossing; within "
           "3 m, stop on 'stop', no collisions (embodied, by the truth)", "embodied", "speech"),
    _bench("localisation", "Monte Carlo localisation in the embodied apartment: tracking, "
           "global localisation, kidnapping", "embodied"),
    _bench("perception", "perception: table-top objects (detection, recognition, position), "
           "people, faces, pointing", "embodied"),
    _bench("guide", "guiding: a person led 6-20 m through doors, lagging or wandering off by "
           "seed; at the goal by the truth, no collisions", "embodied"),
    _bench("manipulation", "manipulation in physics: grasping generated table-top scenes, "
           "physical HRI", "embodied"),
    _bench("speech", "speech: spoken commands heard by the two reconciled decoders, clean and "
           "noisy; rejection", "speech"),
    _bench("console", "the web console: e-stop within one tick (navigation, follow) and 20 "
           "watchers at 10 updates/s", "web", "embodied"),
    _bench("console_fuzz", "the web console under bad requests: 100 MB unauthenticated POSTs "
           "and 10 000 malformed requests (answers, memory)", "web"),
    _bench("transport", "ROS 2 transport: throughput between two processes, fetch over ROS 2, "
           "a lost robot's detection", "ros", "embodied"),
    _bench("serve_fuzz", "malformed requests to homebot sim serve and ros serve over DDS: "
           "every one answered, the servers alive and flat in memory", "ros"),
)


def benchmark_names() -> list[str]:
    """The registered benchmarks' names, in registry order."""
    return [entry.name for entry in BENCHMARKS]


def benchmark(name: str) -> Benchmark:
    """The registered benchmark called ``name``."""
    for entry in BENCHMARKS:
        if entry.name == name:
            return entry
    raise BenchmarkError(f"no benchmark {name!r}: choose one of {', '.join(benchmark_names())}")


def missing_extras(entry: Benchmark) -> list[str]:
    """The extras ``entry`` needs that are not installed (found without importing them)."""
    return [extra for extra in entry.extras
            if any(importlib.util.find_spec(library) is None
                   for library in EXTRA_MODULES[extra])]
