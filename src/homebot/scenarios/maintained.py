"""Self-maintenance runs: a Golog program with its components simulated, crashes and all.

Wires the Golog engine's ``MaintenanceInterpreter`` to the simulator's
``ComponentSimulation`` (ground truth) and judges a run from the simulator's
event log: every task action against every constraint that names it, and
every crash against the next action that depends on the crashed module.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from importlib import resources
from typing import Any

from rich.markup import escape

from homebot.executive import RunReport
from homebot.golog.allen import DISJOINT, Constraint, converse, mask_of, relation_of
from homebot.golog.build import do
from homebot.golog.domains import domain_theory
from homebot.golog.interpreter import ProgramTrace, Report, SimulatedExecutor
from homebot.golog.maintenance import (
    BEGINS_AFTER,
    ENDED_BEFORE,
    MANAGEMENT_ACTIONS,
    Commitment,
    Maintenance,
    MaintenanceExecutor,
    MaintenanceInterpreter,
    add_management,
    maintenance_from_text,
)
from homebot.golog.program import Program
from homebot.golog.theory import GroundAction, State, Theory, action_text
from homebot.sim.components import ComponentSimulation, SimulatedComponent

__all__ = [
    "DURATIONS",
    "ComponentExecutor",
    "MaintenanceTrace",
    "Verdict",
    "judge",
    "run_maintained",
    "shipped_maintenance",
]

#: seconds each task action takes in the simulation (±20 %, seeded)
DURATIONS = {"goto_place": 25.0, "grasp": 10.0, "give": 8.0, "say": 3.0,
             "introduce_yourself_and_the_team": 10.0, "park_arm": 2.0, "extend_arm": 2.0}


def shipped_maintenance(name: str = "rips") -> Maintenance:
    """The maintenance section shipped for a program (``data/maintenance/NAME.yaml``)."""
    path = resources.files("homebot.data") / "maintenance" / f"{name}.yaml"
    return maintenance_from_text(path.read_text(encoding="utf-8"), f"{name}.yaml")


class ComponentExecutor(MaintenanceExecutor):
    """Task actions take simulated time on the components' clock; management actions
    operate the simulated components; a crash that breaks a marker interrupts the action,
    which, done again next, goes on for the time it had left."""

    def __init__(self, theory: Theory, simulation: ComponentSimulation, *, seed: int = 0,
                 durations: Mapping[str, float] | None = None,
                 start_button_after: int = 3) -> None:
        def events(clock: int, truth: State) -> list[GroundAction]:
            pressed = "press_start_button" in theory.actions and clock >= start_button_after
            return [("press_start_button",)] if pressed and truth.get(
                ("start_button",)) != "on" else []

        self.task = SimulatedExecutor(theory, seed=seed, events=events)
        self.simulation = simulation
        self.durations = dict(durations if durations is not None else DURATIONS)
        self.rng = random.Random(f"durations {seed}")
        self.markers: dict[str, tuple[str, bool]] = {}
        self._resume: tuple[GroundAction, float] | None = None  #: interrupted, time left

    def execute(self, action: GroundAction, state: State) -> Report:
        name = str(action[0])
        if name in MANAGEMENT_ACTIONS:
            component = str(action[1])
            target = str(action[2]) if len(action) > 2 else None
            ok = self.simulation.operate(name, component, target)
            return Report(ok, message="" if ok else f"{action_text(action)} did not work: "
                          f"{component} is {self.simulation.state.get(component, 'unknown')}")
        if self._resume is not None and self._resume[0] == action:
            duration = self._resume[1]  # an interrupted action goes on from where it stopped
        else:
            duration = self.durations.get(name, 2.0) * (0.8 + 0.4 * self.rng.random())
        self._resume = None
        began = self.simulation.now
        crashed = self.simulation.task(action_text(action), duration, self.markers)
        if crashed is not None:
            self.interrupted = crashed
            self._resume = (action, max(duration - (self.simulation.now - began), 1e-3))
            return Report(False, message=f"interrupted: {crashed} failed")
        return self.task.execute(action, state)

    def watch(self, markers: Sequence[Commitment]) -> None:
        # a crash makes a module 'failed': per component, watch the marker a crash breaks
        self.markers = {}
        for marker in sorted(markers, key=lambda m: (m.holds, m.state == "failed")):
            self.markers[marker.component] = (marker.state, marker.holds)

    def component_states(self) -> dict[str, str]:
        return dict(self.simulation.state)

    def exogenous(self, state: State) -> list[GroundAction]:
        return self.task.exogenous(state)

    def wait(self, state: State) -> list[GroundAction] | None:
        self.simulation.advance(1.0)
        return self.task.wait(state)


@dataclass
class Verdict:
    """What the event log says about a run."""

    actions: int = 0
    violations: list[str] = field(default_factory=list)
    crashes: int = 0
    repaired: int = 0
    not_needed_again: int = 0
    unrepaired: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {"actions": self.actions, "violations": self.violations,
                "crashes": self.crashes, "repaired_before_dependent_action": self.repaired,
                "not_needed_again": self.not_needed_again,
                "unrepaired": self.unrepaired}


def _timelines(events: Sequence[Mapping[str, Any]]) -> dict[str, list[tuple[float, float, str]]]:
    """Per component, its states as (start, end, state); the last one runs on for ever."""
    changes: dict[str, list[tuple[float, str]]] = {}
    for event in events:
        if event["kind"] == "component":
            changes.setdefault(event["component"], []).append((event["time"], event["state"]))
    timelines = {}
    for component, steps in changes.items():
        spans = []
        for index, (start, state) in enumerate(steps):
            end = steps[index + 1][0] if index + 1 < len(steps) else math.inf
            if end > start:
                spans.append((start, end, state))
        timelines[component] = spans
    return timelines


def judge(events: Sequence[Mapping[str, Any]], maintenance: Maintenance) -> Verdict:
    """Check the run in ``events`` (the simulator's log) against the constraints.

    For every task action interval and every constraint between its action and
    a ``component=state``: under a relation set that keeps the state away on both
    sides (inside ``disjoint``) every interval of that state must stand in it;
    otherwise some interval must. After every crash the module must run again
    when the next action whose constraints (as solved) need it running starts.
    """
    timelines = _timelines(events)
    horizon = max((event["time"] for event in events), default=0.0) + 1e6
    verdict = Verdict()
    starts: dict[str, float] = {}
    intervals: list[tuple[str, float, float]] = []
    for event in events:
        if event["kind"] == "task.start":
            starts[event["action"]] = event["time"]
        elif event["kind"] == "task.end":
            begun = starts.pop(event["action"])
            if event["time"] > begun:
                intervals.append((event["action"], begun, event["time"]))
    by_action: dict[str, list[tuple[Constraint, str, int]]] = {}
    for constraint in maintenance.constraints:
        if "=" not in constraint.subject and "=" in constraint.object:
            by_action.setdefault(constraint.subject, []).append(
                (constraint, constraint.object, constraint.relations))
        elif "=" in constraint.subject and "=" not in constraint.object:
            by_action.setdefault(constraint.object, []).append(
                (constraint, constraint.subject, converse(constraint.relations)))
    for text, begun, ended in intervals:
        verdict.actions += 1
        name = text.split("(")[0]
        for constraint, term, relations in by_action.get(name, []):
            component, state = term.split("=")
            spans = [(start, min(end, horizon)) for start, end, value
                     in timelines.get(component, []) if value == state]
            found = [mask_of(relation_of((begun, ended), span)) for span in spans]
            if relations & ~DISJOINT == 0 and relations & BEGINS_AFTER and \
                    relations & ENDED_BEFORE:
                ok = all(relation & relations for relation in found)
            else:
                ok = any(relation & relations for relation in found)
            if not ok:
                verdict.violations.append(f"{text} at {begun:.1f}-{ended:.1f} s: "
                                          f"{constraint.text}")
    needs = {name: {component for component, state
                    in maintenance.requirements(name).must.items() if state == "running"}
             for name in {text.split("(")[0] for text, _, _ in intervals}}
    crashes = [(event["time"], event["component"]) for event in events
               if event["kind"] == "component" and event["state"] == "failed"]
    for start, component in crashes:
        verdict.crashes += 1
        later = [(begun, text) for text, begun, _ in intervals
                 if begun >= start and component in needs[text.split("(")[0]]]
        if not later:
            verdict.not_needed_again += 1
            continue
        begun, text = min(later)
        if any(s <= begun < e and value == "running" for s, e, value in timelines[component]):
            verdict.repaired += 1
        else:
            verdict.unrepaired.append(f"{component} failed at {start:.1f} s, "
                                      f"{text} started at {begun:.1f} s without it")
    return verdict


@dataclass
class MaintenanceTrace:
    """What a self-maintenance run adds to its report: the program's trace, what the
    simulator's event log says about it, those events, and what the operator was told."""

    program: ProgramTrace
    verdict: Verdict
    events: list[dict[str, Any]]
    operator: list[str]

    @property
    def log(self) -> list[dict[str, Any]]:
        """The interpreter's log: actions, noticed states, repairs, interruptions."""
        return self.program.log

    def to_dict(self) -> dict[str, Any]:
        return {"operator": self.operator, "judged": self.verdict.to_dict(), "log": self.log}

    def lines(self) -> list[str]:
        """Each action (failed ones with why), what was noticed and interrupted, what the
        operator was told; then the crashes and the violated constraints."""
        lines = []
        for entry in self.log:
            if entry["kind"] in ("action", "maintenance.noticed", "maintenance.interrupted",
                                 "maintenance.operator"):
                detail = entry.get("action") or entry.get("component")
                if entry["kind"] == "action" and not entry["ok"]:
                    detail = f"{detail} (failed: {entry['message']})"
                elif entry["kind"] == "maintenance.noticed":
                    detail = f"{detail} is {entry['state']}"
                elif entry["kind"] == "maintenance.operator":
                    detail = f"told the operator: {entry['message']}"
                lines.append(escape(f"{entry['kind']}: {detail}"))
        lines.append(f"{self.verdict.crashes} crash(es), {len(self.verdict.violations)} "
                     "action(s) with a violated constraint")
        return lines


def simulated_components(maintenance: Maintenance, *, seed: int,
                         mean_time_to_failure: float, start_failure: float,
                         restart_failure: float) -> ComponentSimulation:
    """The simulator's copy of the components (modules crash, postures do not)."""
    components = [SimulatedComponent(c.name, c.kind, c.states, c.initial, c.durations)
                  for c in maintenance.components.values()]
    mttf = {c.name: mean_time_to_failure for c in maintenance.components.values()
            if c.kind == "module"}
    return ComponentSimulation(components, seed=seed, mean_time_to_failure=mttf,
                               start_failure=start_failure, restart_failure=restart_failure)


def run_maintained(program: Program | None = None, *, domain: str = "rips",
                   maintenance: Maintenance | None = None, seed: int = 0,
                   mean_time_to_failure: float = 150.0, start_failure: float = 0.05,
                   restart_failure: float = 0.1) -> RunReport[MaintenanceTrace]:
    """Run ``program`` (the domain's own procedure by default) with crashing components."""
    maintenance = maintenance if maintenance is not None else shipped_maintenance(domain)
    theory = add_management(domain_theory(domain), maintenance)
    maintenance.check(theory)
    simulation = simulated_components(maintenance, seed=seed,
                                      mean_time_to_failure=mean_time_to_failure,
                                      start_failure=start_failure,
                                      restart_failure=restart_failure)
    executor = ComponentExecutor(theory, simulation, seed=seed)
    interpreter = MaintenanceInterpreter(theory, executor, maintenance, seed=seed)
    result = interpreter.run(program if program is not None else do(domain))
    verdict = judge(simulation.events, maintenance)
    operator = [entry["message"] for entry in result.detail.log
                if entry["kind"] == "maintenance.operator"]
    return RunReport(result.success, sim_time=simulation.now, reason=result.reason,
                     detail=MaintenanceTrace(result.detail, verdict, simulation.events, operator))
