"""``Skill`` and ``Outcome``: execute, monitor by sensing, report (Care-O-bot §4.1).

A skill's ``execute`` acts and, when it believes it is done, returns ``finished``
(or ``failed`` if it could not act at all). Its ``monitor`` then senses whether
the effect is really there: ``verified`` or ``aborted``. ``run`` ties them
together and retries an aborted (or retryable failed) attempt while the skill's
retry budget lasts, reporting ``retrying`` each time. Once the run's cancel token is
cancelled, it neither monitors nor retries: it ends ``failed`` with the error ``cancelled``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import datetime
from enum import StrEnum
from typing import Any, ClassVar

from homebot.beliefs import Beliefs
from homebot.cancel import CancelToken
from homebot.clock import DEFAULT_START
from homebot.events import EventLog
from homebot.robot import Robot
from homebot.world import PathPlanner, World

__all__ = ["ErrorCode", "Outcome", "Skill", "SkillContext", "Status", "speak", "time_left"]


class Status(StrEnum):
    """Where a skill's execution stands (the Care-O-bot paper's outcomes)."""

    FINISHED = "finished"  #: executed and believed done; not yet checked
    VERIFIED = "verified"  #: the monitoring actions confirmed the effect
    FAILED = "failed"  #: could not be executed (precondition, internal error)
    ABORTED = "aborted"  #: executed, but monitoring does not see the effect
    RETRYING = "retrying"  #: will be tried again


class ErrorCode(StrEnum):
    """Why a skill did not end verified, grouped as in pyrobosim's ExecutionStatus."""

    # precondition
    UNKNOWN_TARGET = "unknown_target"  #: the named place, person or object is not known
    HANDS_FULL = "hands_full"  #: no free hand to pick with
    NOT_HOLDING = "not_holding"  #: nothing in hand to place or give
    NO_PERSON = "no_person"  #: a step needs a person found before it
    # planning / motion
    PATH_BLOCKED = "path_blocked"  #: someone (or something) stands in the way
    DOOR_CLOSED = "door_closed"  #: a closed door is on the way
    NO_PATH = "no_path"  #: no route exists
    # execution / postcondition
    NOT_FOUND = "not_found"  #: the object or person was not seen
    NOT_GRASPED = "not_grasped"  #: the hand is empty after grasping
    WRONG_OBJECT = "wrong_object"  #: the hand holds something else
    NOT_PLACED = "not_placed"  #: the object is not seen where it was put
    NOT_DELIVERED = "not_delivered"  #: the person did not take the object
    NOT_REACHED = "not_reached"  #: the robot is not where it drove to
    LOST_PERSON = "lost_person"  #: the person followed or guided is no longer there
    STOPPED = "stopped"  #: the person walked with showed the stop gesture: the robot stopped
    DOOR_LOCKED = "door_locked"  #: the door did not open
    NO_ANSWER = "no_answer"  #: nobody answered
    # cancelled
    OUT_OF_TIME = "out_of_time"  #: the task's time budget ran out before the step was done
    CANCELLED = "cancelled"  #: the run was cancelled (stop pressed, the goal cancelled)


@dataclass(frozen=True, slots=True)
class Outcome:
    """What a skill reports. True only when ``verified``.

    ``data`` carries results: the object found, the person met, the answer
    heard, the text a count or description produced.
    """

    status: Status
    error: ErrorCode | None = None
    message: str = ""
    data: Mapping[str, Any] = field(default_factory=dict)

    def __bool__(self) -> bool:
        return self.status is Status.VERIFIED

    @classmethod
    def finished(cls, message: str = "", **data: Any) -> Outcome:
        return cls(Status.FINISHED, None, message, data)

    @classmethod
    def verified(cls, message: str = "", **data: Any) -> Outcome:
        return cls(Status.VERIFIED, None, message, data)

    @classmethod
    def failed(cls, error: ErrorCode, message: str, **data: Any) -> Outcome:
        return cls(Status.FAILED, error, message, data)

    @classmethod
    def aborted(cls, error: ErrorCode, message: str, **data: Any) -> Outcome:
        return cls(Status.ABORTED, error, message, data)

    @classmethod
    def cancelled(cls, cancel: CancelToken) -> Outcome:
        """The run was cancelled: failed, ``cancelled``, the token's reason as the message."""
        return cls(Status.FAILED, ErrorCode.CANCELLED, cancel.reason or "cancelled")


@dataclass
class SkillContext:
    """What skills work with: the robot, its map and beliefs, the log, and bindings.

    ``bindings`` holds what earlier steps found: ``person`` (the person last
    found), ``result`` (the text of the last count or description), and, per
    requested object or category, the object actually found. ``deadline`` is the
    robot time (``robot.now()``) by which the task must be over, or None. ``cancel`` is
    the running task's cancel token (the executive gives each task its own): skills check
    it between attempts and in their long loops, and pass it to the robot's motions.
    """

    robot: Robot
    world: World  #: the robot's map and what it was told, not the simulator's truth
    navigator: PathPlanner  #: the global planner on the robot's map
    beliefs: Beliefs
    events: EventLog
    bindings: dict[str, Any] = field(default_factory=dict)
    monitoring: bool = True
    retries: dict[str, int] = field(default_factory=dict)
    deadline: float | None = None
    cancel: CancelToken = field(default_factory=CancelToken)
    #: the calendar date and time at robot time 0 (``robot.now()`` counts from it)
    started_at: datetime = DEFAULT_START


def time_left(context: SkillContext) -> float:
    """Seconds of the task's time budget still left (infinite without a budget)."""
    if context.deadline is None:
        return float("inf")
    return context.deadline - context.robot.now()


def speak(context: SkillContext, text: str) -> None:
    """Say ``text`` and log it as a speech act."""
    context.robot.say(text)
    context.events.record("speech", text=text)


class Skill(ABC):
    """A monitored robot ability. Subclasses set the class attributes and two hooks.

    ``execute(context, args)`` acts and returns ``finished`` or ``failed``; it is
    called once per attempt. ``monitor(context, args, finished)`` senses the
    effect and returns ``verified`` or ``aborted``. Neither blocks on the wall
    clock: the robot port advances simulated time.
    """

    name: ClassVar[str]
    required: ClassVar[tuple[str, ...]] = ()
    optional: ClassVar[tuple[str, ...]] = ()
    retries: ClassVar[int] = 0  #: extra attempts after an aborted one (configurable per run)
    retry_on: ClassVar[frozenset[ErrorCode]] = frozenset()  #: failed errors worth a retry

    @abstractmethod
    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        """Act. Return ``Outcome.finished(...)`` with data, or ``Outcome.failed(...)``."""

    @abstractmethod
    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        """Sense whether the effect is there: ``verified`` (carrying data) or ``aborted``."""

    def assume(self, context: SkillContext, args: Mapping[str, Any], finished: Outcome) -> None:
        """With monitoring off, take the expected effect for granted in the beliefs.

        Most skills change nothing the robot believes; those that do override this.
        """
        return None

    def run(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        """Execute, monitor and report, retrying within the budget; logs every status."""
        budget = context.retries.get(self.name, self.retries) if context.monitoring else 0
        context.events.record("skill.start", skill=self.name, args=dict(args))
        cancel = context.cancel
        attempt = 0
        while True:
            outcome = Outcome.cancelled(cancel) if cancel.cancelled else \
                self.execute(context, args)
            if outcome.status is Status.FINISHED and cancel.cancelled:
                self._report(context, outcome)
                outcome = Outcome.cancelled(cancel)  # stopped: no time spent checking
            if outcome.status is Status.FINISHED:
                self._report(context, outcome)
                if not context.monitoring:
                    self.assume(context, args, outcome)
                    return outcome
                outcome = self.monitor(context, args, outcome)
            if cancel.cancelled and not outcome:
                outcome = Outcome.cancelled(cancel)
            retryable = outcome.status is Status.ABORTED or (
                outcome.status is Status.FAILED and outcome.error in self.retry_on)
            if not retryable or attempt >= budget:
                self._report(context, outcome)
                return outcome
            attempt += 1
            self._report(context, outcome)
            context.events.record("skill.status", skill=self.name, status=Status.RETRYING.value,
                                  attempt=attempt, error=_error(outcome))

    def _report(self, context: SkillContext, outcome: Outcome) -> None:
        context.events.record("skill.status", skill=self.name, status=outcome.status.value,
                              error=_error(outcome), message=outcome.message)


def _error(outcome: Outcome) -> str | None:
    return outcome.error.value if outcome.error else None
