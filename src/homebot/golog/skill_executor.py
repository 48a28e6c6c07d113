"""The executor for the home: each Golog action runs as monitored skills (``homebot.skills``).

A binding turns a ground action into skill steps (none for an action that only
changes the robot's model, such as parking the arm). A step that does not end
verified fails the action, with the skill's message as the reason. While the
program waits (a test or ``waitFor`` that does not hold yet), the ``waiting``
hook is asked what happened meanwhile. ``sensing(action, done)`` reads fluent
values from the robot's beliefs after each action (done or failed), and
``noticing()`` reports exogenous actions the robot saw happen. Every skill step
runs through the executive's ``run_step``: a failed skill goes through its
recovery protocols (door closed, path blocked, object not where expected) before
the action is given up, and once the task's time budget is spent the action fails
and the run stops there (no re-plan).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from homebot.errors import GologError
from homebot.executive import Executive, RunReport
from homebot.executive.recovery import Recover
from homebot.golog.interpreter import Executor, ProgramTrace, Report
from homebot.golog.theory import GroundAction, State, action_text
from homebot.skills import ErrorCode, Status
from homebot.task import Step

__all__ = ["SkillBinding", "SkillExecutor"]

SkillBinding = Callable[[GroundAction], list[Step]]
Waiting = Callable[[State], list[GroundAction] | None]
Sensing = Callable[[GroundAction, bool], Mapping[tuple[Any, ...], Any]]
Noticing = Callable[[], list[GroundAction]]


class SkillExecutor(Executor):
    """Runs actions as skills through the executive; ``steps`` records every skill run.

    ``recover`` narrows which failures the executive may mend (``Executive.run_step``):
    a program that re-plans on a failed action itself may want none.
    """

    def __init__(self, executive: Executive, bindings: Mapping[str, SkillBinding], *,
                 waiting: Waiting | None = None, sensing: Sensing | None = None,
                 noticing: Noticing | None = None, recover: Recover = True) -> None:
        self.executive = executive
        self.context = executive.context
        self.bindings = dict(bindings)
        self.waiting = waiting
        self.sensing = sensing
        self.noticing = noticing
        self.recover = recover
        self.steps: list[dict[str, Any]] = []
        self._began = executive.mark()  # until a run begins

    def begin(self) -> None:
        self._began = self.executive.begin()

    def report(self, success: bool, reason: str,
               trace: ProgramTrace) -> RunReport[ProgramTrace]:
        return self.executive.report(self._began, success, reason, trace)

    def execute(self, action: GroundAction, state: State) -> Report:
        binding = self.bindings.get(str(action[0]))
        if binding is None:
            raise GologError(f"no skill is bound to the action '{action[0]}'; bind it in the "
                             f"executor (bound: {', '.join(sorted(self.bindings))})")
        for step in binding(action):
            outcome = self.executive.run_step(step.skill, step.args, recover=self.recover)
            self.steps.append({"action": action_text(action), "skill": step.skill,
                               **step.args, "status": outcome.status.value,
                               "error": outcome.error.value if outcome.error else None})
            if outcome.status not in (Status.VERIFIED, Status.FINISHED):  # finished: no monitor
                return Report(False, sensed=self._sensed(action, False),
                              message=outcome.message or str(outcome.error),
                              stop=outcome.error is ErrorCode.OUT_OF_TIME)
        return Report(True, sensed=self._sensed(action, True))

    def _sensed(self, action: GroundAction, done: bool) -> Mapping[tuple[Any, ...], Any]:
        return self.sensing(action, done) if self.sensing is not None else {}

    def exogenous(self, state: State) -> list[GroundAction]:
        return self.noticing() if self.noticing is not None else []

    def wait(self, state: State) -> list[GroundAction] | None:
        return self.waiting(state) if self.waiting is not None else None
