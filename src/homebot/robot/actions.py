"""Action semantics for long behaviours: goal, feedback, result, cancel and preempt.

As a ROS 2 action server (and Care-O-bot's SMACH action states, Listing 1–2 of
the Jenny paper) has it: a goal is accepted, runs while giving feedback, and
ends succeeded, aborted or canceled with a result. Here an action advances one
control period per ``step``, on whatever clock its body ticks; ``run`` drives it
to its end. Nothing waits on the wall clock.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from enum import StrEnum
from typing import Generic, TypeVar

__all__ = ["Action", "ActionStatus"]

Goal = TypeVar("Goal")
Feedback = TypeVar("Feedback")
Result = TypeVar("Result")


class ActionStatus(StrEnum):
    """Where an action goal stands (``action_msgs/GoalStatus`` without the transitional states)."""

    ACCEPTED = "accepted"
    EXECUTING = "executing"
    SUCCEEDED = "succeeded"
    ABORTED = "aborted"
    CANCELED = "canceled"

    @property
    def done(self) -> bool:
        return self in (ActionStatus.SUCCEEDED, ActionStatus.ABORTED, ActionStatus.CANCELED)


class Action(ABC, Generic[Goal, Feedback, Result]):
    """One goal of a long behaviour. Subclasses implement ``_step`` and ``_result``.

    ``step`` advances the behaviour by one control period; ``cancel`` asks it to
    stop, which takes effect at the next step (the behaviour may still stop
    the base first). ``on_feedback`` receives every feedback message.
    """

    def __init__(self, goal: Goal,
                 on_feedback: Callable[[Feedback], None] | None = None) -> None:
        self.goal = goal
        self.status = ActionStatus.ACCEPTED
        self.feedback: Feedback | None = None
        self._on_feedback = on_feedback
        self._cancel_requested = False

    def cancel(self) -> None:
        """Ask the behaviour to stop (preempt) at its next step."""
        self._cancel_requested = True

    @property
    def cancel_requested(self) -> bool:
        return self._cancel_requested

    def step(self) -> ActionStatus:
        """One control period of the behaviour; returns the status afterwards."""
        if self.status.done:
            return self.status
        if self._cancel_requested:
            self._on_cancel()
            self.status = ActionStatus.CANCELED
            return self.status
        self.status = ActionStatus.EXECUTING
        outcome = self._step()
        if outcome is not None:
            self.status = outcome
        return self.status

    def publish_feedback(self, feedback: Feedback) -> None:
        self.feedback = feedback
        if self._on_feedback is not None:
            self._on_feedback(feedback)

    def run(self, max_steps: int) -> Result:
        """Step until the action ends (aborting it after ``max_steps``); its result."""
        for _ in range(max_steps):
            if self.step().done:
                break
        else:
            self._on_cancel()
            self.status = ActionStatus.ABORTED
        return self.result()

    @abstractmethod
    def _step(self) -> ActionStatus | None:
        """Advance one period; a final status ends the action, None goes on."""

    @abstractmethod
    def result(self) -> Result:
        """The result (meaningful once the action is done)."""

    def _on_cancel(self) -> None:
        """Bring the behaviour to a safe stop (default: nothing to do)."""
