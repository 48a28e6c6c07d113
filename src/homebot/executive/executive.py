"""``Executive``: the one acting loop. Every skill in homebot runs through it.

``run`` carries out a task of steps (a GPSR parse, a task file); ``run_step`` runs one
step for an engine that sequences skills itself (HTN, Golog, SitLog, the inference
cycle), with the same retries, recovery protocols, inference fallback and time budget.
``begin`` and ``report`` frame an engine's run into the one ``RunReport``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from homebot.cancel import CancelToken
from homebot.executive.recovery import PROTOCOLS, Protocol, Recover
from homebot.executive.report import DetailT, RunReport, StepReport
from homebot.skills import (
    OPERATOR,
    ErrorCode,
    Outcome,
    SkillContext,
    Status,
    skill_named,
    speak,
)
from homebot.skills.skill import time_left
from homebot.task import Step, Task

__all__ = ["Executive", "RunMark"]

# How many recovery protocols one step may use before the executive gives up on it.
_MAX_RECOVERIES = 4


@dataclass(frozen=True, slots=True)
class RunMark:
    """Where a run began: robot time, the event log's length, the journal's length."""

    time: float
    event: int
    step: int


class Executive:
    """Runs tasks, and the steps of every engine, on one robot.

    With ``recovery`` on, a step that fails or is aborted after its own retries
    goes through the recovery protocols (door closed, path blocked, object or
    person not where expected) and is run again; when nothing applies, the
    robot stops safely, goes back to the operator and says what failed and why.
    With monitoring off in the context, it is a plain sequence, as in the
    monolithic state machines the Care-O-bot paper replaced.

    ``inference`` is the daily-life inference cycle (Golem-III §7), called with
    the protocol signature when no recovery protocol applies or the protocols
    gave up; when an object is not where it was expected (a find or pick ends
    ``not_found``) it is called instead of the blind search protocol, since
    diagnosing where it went is what it is for.

    ``time_limit`` (simulated seconds) is each task's time budget: a step is not
    started once it is spent, recovery stops, and searches stop when a look and
    the way back to the operator no longer fit in it.
    """

    def __init__(self, context: SkillContext, *, recovery: bool = True,
                 inference: Protocol | None = None, time_limit: float | None = None) -> None:
        self.context = context
        self.recovery = recovery and context.monitoring
        self.inference = inference if self.recovery else None
        self.time_limit = time_limit
        self.journal: list[StepReport] = []  #: every step ``run_step`` ran, in order

    def run(self, task: Task, *, interrupt: Callable[[], bool] | None = None,
            cancel: CancelToken | None = None) -> RunReport[None]:
        """Run every step in order; the report says whether all ended as expected.

        ``interrupt`` is asked before each step after the first; when it answers true
        ("stop", "cancel" heard), the task ends there, unfinished, and the robot says so.
        ``cancel`` (None: a token nobody cancels) stops the task the same way, at once: the
        running skill ends ``cancelled`` without recovery, and the report's reason is the
        token's.
        """
        context = self.context
        context.cancel = cancel if cancel is not None else CancelToken()
        started = context.robot.now()
        self.start_budget()
        first_event = context.events.count
        context.events.record("task.start", description=task.description,
                              steps=task.to_dicts())
        reports: list[StepReport] = []
        reason = ""
        for index, step in enumerate(task.steps):
            # A search is a new search ("bring me two drinks" looks for a second drink),
            # so its object is not bound to what an earlier search found.
            args = dict(step.args) if step.skill == "find_object" else self._bind(step.args)
            if context.cancel.cancelled or (index and interrupt is not None and interrupt()):
                reason = context.cancel.reason or "stopped"
                self._stopped(index)
                break
            outcome, recoveries = self._step(step.skill, args)
            handled = outcome.data.get("object")
            if (step.skill == "pick" and recoveries and isinstance(handled, str)
                    and handled != args.get("object")):
                # Recovery took another object (the one offered when the asked one ran
                # out): the report says what was really picked.
                args = {**args, "object": handled}
            reports.append(StepReport(step.skill, args, outcome.status.value,
                                      outcome.error.value if outcome.error else None,
                                      outcome.message, tuple(recoveries)))
            self._remember(step, outcome)
            if outcome.error is ErrorCode.CANCELLED:
                reason = outcome.message
                self._stopped(index)
                break
            if outcome.status in (Status.FAILED, Status.ABORTED):
                reason = outcome.message or (outcome.error.value if outcome.error else "")
                self._tell_operator_failure(index, step, reason)
                break
        success = len(reports) == len(task.steps) and all(
            report.status in (Status.VERIFIED.value, Status.FINISHED.value) for report in reports)
        if success and context.monitoring:
            speak(context, "I have done what you asked.")
        context.events.record("task.end", success=success, reason=reason)
        speech = [event.data["text"] for event in context.events.since(first_event)
                  if event.kind == "speech"]
        return RunReport(success, reports, speech, context.robot.now() - started, reason, None)

    def begin(self, cancel: CancelToken | None = None) -> RunMark:
        """An engine's run starts: the time budget starts now; ``report`` covers what follows.

        ``cancel`` (None: a token nobody cancels) is the run's cancel token, as for ``run``:
        once it is cancelled, ``run_step`` ends each step ``cancelled`` without recovery.
        """
        self.context.cancel = cancel if cancel is not None else CancelToken()
        self.start_budget()
        return self.mark()

    def mark(self) -> RunMark:
        """Where things stand now (robot time, events, steps), for ``report``."""
        return RunMark(self.context.robot.now(), self.context.events.count, len(self.journal))

    def report(self, mark: RunMark, success: bool, reason: str,
               detail: DetailT) -> RunReport[DetailT]:
        """The run report of an engine's run begun at ``mark``: the steps ``run_step`` ran
        since, what the robot said since, and the engine's own ``detail``."""
        context = self.context
        speech = [event.data["text"] for event in context.events.since(mark.event)
                  if event.kind == "speech"]
        return RunReport(success, self.journal[mark.step:], speech,
                         context.robot.now() - mark.time, reason, detail)

    def start_budget(self) -> None:
        """Start the time budget now (``run`` does; engines that call ``run_step`` may)."""
        if self.time_limit is not None:
            self.context.deadline = self.context.robot.now() + self.time_limit
        else:
            self.context.deadline = None

    def run_step(self, skill: str, args: Mapping[str, Any], *, recover: Recover = True,
                 retries: int | None = None) -> Outcome:
        """Run one skill step as a task's step would be: the one place every engine's
        skills run (HTN operators, Golog actions, SitLog situations, the inference cycle).

        The step is not started once the time budget is spent (an ``out_of_time``
        failure); it runs with the skill's retries (``retries`` extra attempts instead,
        if given); a failure then goes through the recovery protocols and, where none
        applies, the inference cycle. ``recover`` narrows which failures may be mended:
        True every one, False none, or the error codes the engine leaves to the executive
        (an engine that handles the rest itself: HTN replans, a dialogue model branches).
        The engine decides what happens next. The first step starts the time budget
        when ``start_budget`` was not called.
        """
        if self.time_limit is not None and self.context.deadline is None:
            self.start_budget()
        args = self._bind(args)
        outcome, recoveries = self._step(skill, args, recover=recover, retries=retries)
        self.journal.append(StepReport(skill, dict(args), outcome.status.value,
                                       outcome.error.value if outcome.error else None,
                                       outcome.message, tuple(recoveries)))
        return outcome

    def _step(self, skill: str, args: Mapping[str, Any], *, recover: Recover = True,
              retries: int | None = None) -> tuple[Outcome, list[str]]:
        """A task's step: refused once the budget is spent, else run with recovery."""
        if time_left(self.context) <= 0:
            return Outcome.failed(ErrorCode.OUT_OF_TIME,
                                  f"I ran out of time before I could {skill}"), []
        budgets = self.context.retries
        previous = budgets.get(skill)
        if retries is not None:
            budgets[skill] = retries
        try:
            return self._run_step(skill, args, recover=recover)
        finally:
            if retries is not None:
                if previous is None:
                    budgets.pop(skill, None)
                else:
                    budgets[skill] = previous

    def _run_step(self, skill: str, args: Mapping[str, Any], depth: int = 0, *,
                  recover: Recover = True) -> tuple[Outcome, list[str]]:
        outcome = self._skill(skill, args)
        recoveries: list[str] = []

        def nested(name: str, nested_args: Mapping[str, Any], *,
                   recover: Recover = True) -> Outcome:
            # Steps a protocol runs may recover too, one level deep.
            if depth >= 1 or recover is False:
                return self._skill(name, nested_args)
            return self._run_step(name, nested_args, depth + 1, recover=recover)[0]

        # Inference serves the task's own steps, not the steps a protocol runs.
        inference = self.inference if depth == 0 else None
        inferred = gave_up = False
        while (self.recovery and not outcome and len(recoveries) < _MAX_RECOVERIES
               and _mendable(outcome, recover) and time_left(self.context) > 0):
            protocol = self._protocol_for(skill, outcome, inference, inferred, gave_up)
            if protocol is None or (depth > 0 and outcome.error is ErrorCode.NOT_FOUND):
                break  # a search a protocol runs does not start searches of its own
            inferred = inferred or protocol is inference
            recoveries.append(outcome.error.value if outcome.error else outcome.status.value)
            self.context.events.record("recovery", skill=skill, error=recoveries[-1],
                                       inference=protocol is inference)
            recovered = protocol(self.context, skill, args, outcome, nested)
            if isinstance(recovered, Outcome):
                outcome = recovered
                if outcome or protocol is inference:
                    continue
                # A protocol's own failure (where it searched) is the step's word now;
                # as when it gives up, inference may still try once.
                recovered = False
            if not recovered:
                if inference is not None and not inferred:
                    gave_up = True  # the protocols gave up: let inference try once
                    continue
                break
            args = self._bind(args)
            outcome = self._skill(skill, args)
        return outcome, recoveries

    def _skill(self, skill: str, args: Mapping[str, Any]) -> Outcome:
        """Run the skill itself: the one call of a skill in homebot."""
        return skill_named(skill).run(self.context, args)

    @staticmethod
    def _protocol_for(skill: str, outcome: Outcome, inference: Protocol | None,
                      inferred: bool, gave_up: bool) -> Protocol | None:
        """The recovery protocol for a failed outcome, or the inference cycle, or None."""
        misplaced = outcome.error is ErrorCode.NOT_FOUND and skill in {"find_object", "pick"}
        if inference is not None and not inferred and (
                misplaced or gave_up or outcome.error not in PROTOCOLS):
            return inference
        if outcome.error is not None and outcome.error in PROTOCOLS and not (
                misplaced and inferred):
            return PROTOCOLS[outcome.error]
        return None

    def _bind(self, args: Mapping[str, Any]) -> dict[str, Any]:
        """Replace a requested object or category by the object actually found for it."""
        bound = dict(args)
        wanted = bound.get("object")
        if isinstance(wanted, str) and f"object:{wanted}" in self.context.bindings:
            bound["object"] = self.context.bindings[f"object:{wanted}"]
        return bound

    def _remember(self, step: Step, outcome: Outcome) -> None:
        if step.skill == "find_object" and outcome.data.get("object"):
            found = outcome.data["object"]
            self.context.bindings[f"object:{step.args['object']}"] = found
            self.context.bindings[f"placement:{found}"] = outcome.data.get("placement")
        if step.skill == "find_person" and outcome.data.get("person"):
            self.context.bindings["person"] = outcome.data["person"]

    def _stopped(self, index: int) -> None:
        """The task stops before (or in) step ``index``, where the robot is; it says so."""
        self.context.events.record("task.interrupted", step=index)
        if self.context.monitoring:
            speak(self.context, "All right, I stopped.")

    def _tell_operator_failure(self, index: int, step: Step, reason: str) -> None:
        context = self.context
        if not context.monitoring:
            return
        # Stop safely: put nothing down, go back to the operator and explain.
        self._skill("navigate", {"to": OPERATOR})
        speak(context, f"I am sorry, I could not finish step {index + 1} ({step.skill}): "
                       f"{reason}.")


def _mendable(outcome: Outcome, recover: Recover) -> bool:
    """Whether recovery may try to mend this failure: never when time is out or the run
    was cancelled."""
    if outcome.error in (ErrorCode.OUT_OF_TIME, ErrorCode.CANCELLED) or recover is False:
        return False
    return recover is True or outcome.error in recover
