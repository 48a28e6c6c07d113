"""The online interpreter (IndiGolog style) with a pluggable executor.

Each cycle takes in the exogenous actions the executor reports, stops if the
program may end, else takes the first transition the program offers: an action
goes to the executor, whose report (nature's outcome of a stochastic action,
sensed fluent values) progresses the robot's model; a ``solve`` plans a policy
whose markers are checked as it runs, and a marker whose value changed sends
the program back to that ``solve`` (re-planning). When no transition is
possible the interpreter waits for the executor to report something new.
"""

from __future__ import annotations

import random
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from rich.markup import escape

from homebot.executive.report import RunReport
from homebot.golog.checking import check_program, check_theory
from homebot.golog.policy import Result, policy_actions
from homebot.golog.program import Program
from homebot.golog.semantics import (
    ActionStep,
    ChanceStep,
    PlanStep,
    ReplanStep,
    SenseStep,
    Step,
    final,
    transitions,
)
from homebot.golog.theory import GroundAction, Situation, State, Theory, action_text

__all__ = ["Executor", "Interpreter", "ProgramTrace", "Report", "SimulatedExecutor"]

ExogenousSource = Callable[[int, State], list[GroundAction]]


@dataclass(frozen=True)
class Report:
    """What an executor tells after an action: done or not, nature's outcome, sensed values.

    ``stop`` says the run cannot go on (the task's time budget is spent): the failed
    action ends the run, with no re-plan.
    """

    ok: bool = True
    outcome: GroundAction | None = None
    sensed: Mapping[tuple[Any, ...], Any] = field(default_factory=dict)
    message: str = ""
    stop: bool = False

    def __bool__(self) -> bool:
        return self.ok


class Executor(ABC):
    """Carries out primitive actions in some world and reports what happened."""

    def begin(self) -> None:
        """A run starts (an executor on a robot starts the task's time budget)."""
        return None

    def report(self, success: bool, reason: str,
               trace: ProgramTrace) -> RunReport[ProgramTrace]:
        """The run's report; an executor on a robot adds the steps it ran, what the robot
        said and the time it took."""
        return RunReport(success, reason=reason, detail=trace)

    @abstractmethod
    def execute(self, action: GroundAction, state: State) -> Report:
        """Do ``action`` (``state`` is what the robot believes); report the result."""

    def exogenous(self, state: State) -> list[GroundAction]:
        """Exogenous actions that happened since the last call (none by default)."""
        return []

    def wait(self, state: State) -> list[GroundAction] | None:
        """The program is blocked: wait; exogenous actions meanwhile, or None if nothing
        will ever happen."""
        return None


class SimulatedExecutor(Executor):
    """A pure simulation of the theory: true state apart from beliefs, seeded outcomes.

    ``events(clock, truth)`` scripts exogenous actions: the clock counts executed
    actions and waits, and each clock value is asked once. With ``observed`` off
    they change the truth unseen: the robot learns of them only by sensing, or
    when an action they made impossible fails.
    """

    def __init__(self, theory: Theory, *, seed: int = 0, truth: State | None = None,
                 events: ExogenousSource | None = None, patience: int = 20,
                 observed: bool = True) -> None:
        self.theory = theory
        self.observed = observed
        self.truth = truth if truth is not None else theory.initial
        self.rng = random.Random(seed)
        self.events = events
        self.clock = 0
        self.patience = patience
        self._asked = -1

    def execute(self, action: GroundAction, state: State) -> Report:
        theory = self.theory
        self.clock += 1
        if not theory.possible(action, self.truth):
            return Report(False, sensed=self._sensed(action),
                          message=f"{action_text(action)} is not possible")
        outcome = None
        chosen = action
        if theory.schema(action).stochastic:
            outcomes = [(nature, chance) for nature, chance in theory.outcomes(action, self.truth)
                        if theory.possible(nature, self.truth)]
            draw, total = self.rng.random(), 0.0
            chosen = outcomes[-1][0]
            for nature, chance in outcomes:
                total += chance
                if draw < total:
                    chosen = nature
                    break
            outcome = chosen
        self.truth = theory.do(chosen, self.truth)
        return Report(True, outcome, self._sensed(action))

    def _sensed(self, action: GroundAction) -> dict[tuple[Any, ...], Any]:
        """The true values of what a sensing action senses (after it, or after it failed)."""
        schema = self.theory.schema(action)
        if schema.senses is None:
            return {}
        return {key: self.truth.get(key, self.theory.fluents[key[0]].default)
                for key in schema.senses(*action[1:])}

    def exogenous(self, state: State) -> list[GroundAction]:
        if self.events is None or self._asked >= self.clock:
            return []
        self._asked = self.clock
        happened = list(self.events(self.clock, self.truth))
        for action in happened:
            self.truth = self.theory.do(action, self.truth)
        return happened if self.observed else []

    def wait(self, state: State) -> list[GroundAction] | None:
        if self.patience <= 0:
            return None
        self.patience -= 1
        self.clock += 1
        return self.exogenous(state)


@dataclass
class ProgramTrace:
    """What a Golog run adds to its report: the state reached, the actions done (the
    history), the log of actions, plans, re-plans, sensing and waits, and the plans made."""

    state: State
    history: list[GroundAction] = field(default_factory=list)
    log: list[dict[str, Any]] = field(default_factory=list)
    plans: list[Result] = field(default_factory=list)
    replans: int = 0

    @property
    def situation(self) -> Situation:
        """The situation reached: the state with the history of actions that led to it."""
        return Situation(self.state, tuple(self.history))

    @property
    def actions(self) -> list[str]:
        """The executed actions as text."""
        return [action_text(action) for action in self.history]

    def to_dict(self) -> dict[str, Any]:
        return {"actions": self.actions, "log": self.log, "replans": self.replans}

    def lines(self) -> list[str]:
        """Each action, exogenous action, re-plan and sensing result, in order."""
        lines = []
        for entry in self.log:
            if entry["kind"] in ("action", "exogenous", "replan", "sensed"):
                detail = entry.get("action") or entry.get("outcome") or entry.get("marker")
                lines.append(escape(f"{entry['kind']}: {detail}"))
        return lines


class Interpreter:
    """Runs programs online over one theory and one executor; seeded for ``prob``.

    ``listener`` sees every log entry as it happens (actions, plans, re-plans,
    exogenous actions, sensing results, waits).
    """

    def __init__(self, theory: Theory, executor: Executor, *, seed: int = 0,
                 max_steps: int = 2000, max_replans: int = 25,
                 listener: Callable[[dict[str, Any]], None] | None = None) -> None:
        self.theory = theory
        self.executor = executor
        self.listener = listener
        self.rng = random.Random(seed)
        self.max_steps = max_steps
        self.max_replans = max_replans

    def run(self, program: Program, state: State | None = None) -> RunReport[ProgramTrace]:
        """Execute ``program`` from ``state`` (the theory's initial state by default).

        The program and the theory's procedures are checked first: an unknown
        name or a wrong number of arguments raises ``GologError``.
        """
        theory = self.theory
        check_theory(theory)
        check_program(theory, program)
        trace = ProgramTrace(state if state is not None else theory.initial)
        self.executor.begin()
        failure = self._run(program, trace)
        return self.executor.report(not failure, failure, trace)

    def _run(self, program: Program, run: ProgramTrace) -> str:
        """Run ``program`` from the trace's state to its end; why it failed, or ""."""
        theory = self.theory
        state = run.state
        configuration = program
        for _ in range(self.max_steps):
            for action in self.executor.exogenous(state):
                state = self._exogenous(run, action, state)
            if final(configuration, state, theory):
                run.state = state
                return ""
            found = transitions(configuration, state, theory)
            if not found:
                happened = self.executor.wait(state)
                if happened is None:
                    return self._failed(run, state, "the program is blocked and nothing "
                                                    "more will happen")
                self._log(run, {"kind": "wait"})
                for action in happened:
                    state = self._exogenous(run, action, state)
                continue
            step, configuration = self._pick(found)
            if isinstance(step, ActionStep):
                state, configuration, failure = self._execute(run, step, state, configuration)
            else:
                failure = self._note(run, step)
            if failure:
                return self._failed(run, state, failure)
        return self._failed(run, state, f"no end after {self.max_steps} steps")

    def _execute(self, run: ProgramTrace, step: ActionStep, state: State,
                 remaining: Program) -> tuple[State, Program, str]:
        """Have the executor do an action; the new state, what remains, and any failure."""
        report = self.executor.execute(step.action, state)
        text = action_text(step.action)
        self._log(run, {"kind": "action", "action": text, "ok": report.ok,
                        "message": report.message})
        if report:
            run.history.append(step.action)
            return self._progress(step.action, report, state), remaining, ""
        state = state.progressed(report.sensed) if report.sensed else state
        if step.fallback is None or run.replans >= self.max_replans or report.stop:
            return state, remaining, f"{text} failed: {report.message}"
        # A planned action failed: the policy's model of the world was wrong; plan again.
        run.replans += 1
        self._log(run, {"kind": "replan", "marker": f"done({text})", "expected": True,
                        "message": report.message})
        return state, step.fallback, ""

    def _note(self, run: ProgramTrace, step: Step) -> str:
        """Log a step that is not an action; the failure it means, if any."""
        if isinstance(step, PlanStep):
            run.plans.append(step.result)
            self._log(run, {"kind": "plan", "value": step.result.value,
                            "probability": step.result.probability,
                            "actions": [action_text(action)
                                        for action in policy_actions(step.result.policy)]})
        elif isinstance(step, ReplanStep):
            run.replans += 1
            self._log(run, {"kind": "replan", "marker": str(step.condition),
                            "expected": step.expected})
            if run.replans > self.max_replans:
                return "too many re-plans"
        elif isinstance(step, SenseStep):
            self._log(run, {"kind": "sensed", "outcome": action_text(step.nature)})
        return ""

    def _log(self, run: ProgramTrace, entry: dict[str, Any]) -> None:
        """Keep a log entry with the run and pass it to the listener (an event log, say)."""
        run.log.append(entry)
        if self.listener is not None:
            self.listener(entry)

    def _pick(self, found: list[tuple[Step, Program]]) -> tuple[Step, Program]:
        step, remaining = found[0]
        if not isinstance(step, ChanceStep):
            return step, remaining
        chances = [(s, rest) for s, rest in found if isinstance(s, ChanceStep)]
        draw, total = self.rng.random(), 0.0
        for chance, rest in chances:
            total += chance.probability
            if draw < total:
                return chance, rest
        return chances[-1]

    def _progress(self, action: GroundAction, report: Report, state: State) -> State:
        theory = self.theory
        if theory.schema(action).stochastic:
            if report.outcome is not None:
                state = theory.do(report.outcome, state)
        else:
            state = theory.do(action, state)
        return state.progressed(report.sensed) if report.sensed else state

    def _exogenous(self, run: ProgramTrace, action: GroundAction, state: State) -> State:
        self._log(run, {"kind": "exogenous", "action": action_text(action)})
        return self.theory.do(action, state)

    @staticmethod
    def _failed(run: ProgramTrace, state: State, reason: str) -> str:
        run.state = state
        return reason
