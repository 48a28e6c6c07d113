"""Self-maintenance: RIPS with crashing components (completion, repairs, violations) and speed.

Repairs: ``--runs`` seeded runs of the RIPS program with the shipped maintenance
section; modules crash after exponentially distributed running times (mean
``--mttf`` seconds), starts fail 5 % and restarts 10 % of the time. Each run is
judged from the simulator's event log (``homebot.scenarios.maintained.judge``):
actions run with a violated constraint, crashes repaired before the next action
that needs the module. Speed: the time the transformation plus solving adds
per task action, for a generated section of ``--components`` components and
``--constraints`` constraints; three ways: everything solved from scratch per
action, the state network solved once and each action's network per action (as
CAESAR formulates a CSP for the next action), and each action's requirements
cached by action name.
"""

from __future__ import annotations

import argparse
import random
import statistics
import time
from collections import Counter
from typing import Any

from rich.console import Console

from homebot.bench.arguments import count, seed
from homebot.errors import GologError
from homebot.golog.allen import DISJOINT, WITHIN, Constraint, mask_of
from homebot.golog.maintenance import MODULE_STATES, Component, Maintenance
from homebot.golog.program import Call, Nil, Seq
from homebot.progress import track
from homebot.scenarios.maintained import run_maintained, shipped_maintenance

__all__ = ["add_arguments", "run", "synthetic_maintenance"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--runs", type=count("--runs", 1, 10_000), default=200,
                        help="seeded RIPS runs with crashes")
    parser.add_argument("--seed", type=seed, default=0, help="the first run's seed")
    parser.add_argument("--mttf", type=count("--mttf", 10, 100_000), default=150,
                        help="mean seconds a module runs before it crashes")
    parser.add_argument("--components", type=count("--components", 2, 100), default=10)
    parser.add_argument("--constraints", type=count("--constraints", 1, 1000), default=30)
    parser.add_argument("--actions", type=count("--actions", 1, 1_000_000), default=2000,
                        help="task actions timed per way of solving")


def synthetic_maintenance(rng: random.Random, components: int = 10,
                          constraints: int = 30) -> Maintenance:
    """A consistent generated section: modules and two-state postures, constraints between
    task actions and states (within, disjoint, before) and between module states (within)."""
    postures = max(1, components // 5)
    parts = {f"m{i}": Component(f"m{i}", "module", MODULE_STATES, "off", _durations())
             for i in range(components - postures)}
    parts.update({f"p{i}": Component(f"p{i}", "posture", ("parked", "unparked"), "parked",
                                     _durations()) for i in range(postures)})
    modules = [name for name, part in parts.items() if part.kind == "module"]
    actions = [f"a{i}" for i in range(max(2, constraints // 5))]
    for _ in range(1000):
        chosen: list[Constraint] = []
        used: set[tuple[str, str]] = set()
        between = min(len(modules) - 1, constraints // 5)
        for index in range(between):  # a chain of modules, each within one started earlier
            inner, outer = modules[index + 1], rng.choice(modules[: index + 1])
            chosen.append(Constraint(f"{inner}=running", WITHIN, f"{outer}=running",
                                     f"{inner}=running within {outer}=running"))
        while len(chosen) < constraints:
            action, name = rng.choice(actions), rng.choice(list(parts))
            if (action, name) in used:
                continue
            used.add((action, name))
            if parts[name].kind == "module":
                relation, state = rng.choice([("within", "running"), ("within", "running"),
                                              ("disjoint", "running")])
            else:
                relation, state = rng.choice([("within", "unparked"), ("disjoint", "unparked"),
                                              ("before", "parked")])
            mask = {"within": WITHIN, "disjoint": DISJOINT, "before": mask_of("before")}[relation]
            chosen.append(Constraint(action, mask, f"{name}={state}",
                                     f"{action} {relation} {name}={state}"))
        try:
            return Maintenance(parts, chosen, source="generated")
        except GologError:
            continue  # inconsistent draw: draw again
    raise GologError("no consistent constraint set drawn in 1000 tries; lower --constraints")


def _durations() -> dict[str, float]:
    return {"start": 1.0, "stop": 0.5, "restart": 2.0, "set_posture": 2.0}


def _timed(maintenance: Maintenance, rng: random.Random, actions: int,
           how: str) -> dict[str, float]:
    """Per task action: solve (as ``how`` says), plan the prefix and build δ′; ms figures."""
    names = sorted(maintenance.actions)
    parts = maintenance.components
    samples = []
    for _ in range(actions):
        action = rng.choice(names)
        states = {name: rng.choice(part.states) for name, part in parts.items()}
        began = time.perf_counter()
        if how == "from scratch":
            maintenance.forget()
        requirements = maintenance.requirements(action, cached=how == "cached")
        prefix = maintenance.plan(states, requirements)
        Seq((*(Call(str(m[0])) for m in prefix), Call(action), Nil()))
        samples.append(1000 * (time.perf_counter() - began))
    samples.sort()
    return {"mean_ms": round(statistics.fmean(samples), 4),
            "median_ms": round(samples[len(samples) // 2], 4),
            "p95_ms": round(samples[int(0.95 * (len(samples) - 1))], 4),
            "max_ms": round(samples[-1], 4)}


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Repair figures over the seeded runs, then the per-action cost of self-maintenance."""
    runs, first = getattr(args, "runs", 200), getattr(args, "seed", 0)
    mttf = float(getattr(args, "mttf", 150))
    completed = violations = crashes = repaired = unneeded = unrepaired = actions = 0
    interruptions = 0
    told: Counter[str] = Counter()
    failures: Counter[str] = Counter()
    examples: list[str] = []
    sim_time = []
    for index in track(range(runs), "maintained runs"):
        result = run_maintained(seed=first + index, mean_time_to_failure=mttf)
        verdict = result.detail.verdict
        completed += result.success
        actions += verdict.actions
        violations += len(verdict.violations)
        crashes += verdict.crashes
        repaired += verdict.repaired
        unneeded += verdict.not_needed_again
        unrepaired += len(verdict.unrepaired)
        examples += (verdict.violations + verdict.unrepaired)[:1]
        interruptions += sum(e["kind"] == "maintenance.interrupted" for e in result.detail.log)
        for message in result.detail.operator:
            told[message.split()[1]] += 1
        if not result.success:
            failures[result.reason.split(":")[0] if not result.detail.operator
                     else "operator told"] += 1
        sim_time.append(result.sim_time)
    repairs = {
        "program": "rips", "runs": runs, "first_seed": first, "mttf_s": mttf,
        "completed": completed, "completed_percent": round(100 * completed / runs, 1),
        "task_actions_judged": actions, "actions_with_violated_constraint": violations,
        "crashes": crashes, "repaired_before_dependent_action": repaired,
        "crashes_not_needed_again": unneeded, "crashes_unrepaired": unrepaired,
        "actions_interrupted_by_crash": interruptions, "operator_told": dict(told),
        "failures": dict(failures), "examples": examples[:5],
        "mean_sim_time_s": round(statistics.fmean(sim_time), 1)}
    components, constraints = getattr(args, "components", 10), getattr(args, "constraints", 30)
    timed_actions = getattr(args, "actions", 2000)
    rng = random.Random(first)
    generated = synthetic_maintenance(rng, components, constraints)
    speed: dict[str, Any] = {"components": components, "constraints": len(generated.constraints),
                             "intervals": len(generated.states) + 1,
                             "actions_timed": timed_actions}
    for how in ("from scratch", "per action", "cached"):
        speed[how] = _timed(generated, random.Random(first), timed_actions, how)
    rips = shipped_maintenance("rips")
    speed["rips section (7 components, 15 constraints), per action"] = _timed(
        rips, random.Random(first), timed_actions, "per action")
    if console is not None:
        console.print(f"repairs: {repairs}", highlight=False)
        for key, value in speed.items():
            console.print(f"speed {key}: {value}", highlight=False)
    return {"benchmark": "maintenance", "repairs": repairs, "speed": speed}
