"""The executor for the home: each Golog action runs as monitored skills (``homebot.skills``).

A binding turns a ground action into skill steps (none for an action that only
changes the robot's model, such as parking the arm). A step that does not end
verified fails the action, with the skill's message as the reason. While the
program waits (a test or ``waitFor`` that does not hold yet), the ``waiting``
hook is asked what happened meanwhile. ``sensing(action, done)`` reads fluent
values from the robot's beliefs after each action (done or failed), and
``noticing()`` reports exogenous actions the robot saw happen. With ``recovery``
on, a failed skill goes
through the executive's recovery protocols (door closed, path blocked, object
not where expected) before the action is given up.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from homebot.errors import GologError
from homebot.executive import PROTOCOLS
from homebot.golog.interpreter import Executor, Report
from homebot.golog.theory import GroundAction, State, action_text
from homebot.skills import Outcome, SkillContext, Status, skill_named
from homebot.task import Step

__all__ = ["SkillBinding", "SkillExecutor"]

SkillBinding = Callable[[GroundAction], list[Step]]
Waiting = Callable[[State], list[GroundAction] | None]
Sensing = Callable[[GroundAction, bool], Mapping[tuple[Any, ...], Any]]
Noticing = Callable[[], list[GroundAction]]

# How many recovery protocols one skill step may use before the action fails.
_MAX_RECOVERIES = 3


class SkillExecutor(Executor):
    """Runs actions as skills in a ``SkillContext``; ``steps`` records every skill run."""

    def __init__(self, context: SkillContext, bindings: Mapping[str, SkillBinding], *,
                 waiting: Waiting | None = None, sensing: Sensing | None = None,
                 noticing: Noticing | None = None, recovery: bool = True) -> None:
        self.context = context
        self.bindings = dict(bindings)
        self.waiting = waiting
        self.sensing = sensing
        self.noticing = noticing
        self.recovery = recovery and context.monitoring
        self.steps: list[dict[str, Any]] = []

    def execute(self, action: GroundAction, state: State) -> Report:
        binding = self.bindings.get(str(action[0]))
        if binding is None:
            raise GologError(f"no skill is bound to the action '{action[0]}'; bind it in the "
                             f"executor (bound: {', '.join(sorted(self.bindings))})")
        for step in binding(action):
            outcome = self._run(step)
            self.steps.append({"action": action_text(action), "skill": step.skill,
                               **step.args, "status": outcome.status.value,
                               "error": outcome.error.value if outcome.error else None})
            if outcome.status not in (Status.VERIFIED, Status.FINISHED):  # finished: no monitor
                return Report(False, sensed=self._sensed(action, False),
                              message=outcome.message or str(outcome.error))
        return Report(True, sensed=self._sensed(action, True))

    def _sensed(self, action: GroundAction, done: bool) -> Mapping[tuple[Any, ...], Any]:
        return self.sensing(action, done) if self.sensing is not None else {}

    def exogenous(self, state: State) -> list[GroundAction]:
        return self.noticing() if self.noticing is not None else []

    def _run(self, step: Step) -> Outcome:
        context = self.context
        outcome = skill_named(step.skill).run(context, step.args)
        for _ in range(_MAX_RECOVERIES if self.recovery else 0):
            protocol = PROTOCOLS.get(outcome.error) if outcome.error else None
            if outcome or protocol is None:
                break
            context.events.record("recovery", skill=step.skill, error=str(outcome.error),
                                  inference=False)
            recovered = protocol(context, step.skill, step.args, outcome,
                                 lambda name, args: skill_named(name).run(context, args))
            if isinstance(recovered, Outcome):
                outcome = recovered
            elif recovered:
                outcome = skill_named(step.skill).run(context, step.args)
            else:
                break
        return outcome

    def wait(self, state: State) -> list[GroundAction] | None:
        return self.waiting(state) if self.waiting is not None else None
