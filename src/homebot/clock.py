"""``Clock``: simulated time that only actions advance, watched by observers.

Nothing here reads the wall clock. Whoever needs to see time pass (the web console, which
paces a run against the wall clock; a recorder) registers an observer, called with the
time before and after each advance. An observer may ask for long advances to be cut into
steps, each observed, so that it sees time pass smoothly; the steps add up to exactly the
advance asked for.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from datetime import datetime

from homebot.cancel import CancelToken

__all__ = ["DEFAULT_START", "Clock", "ClockObserver", "start_time"]

#: the calendar date and time a run starts at unless told otherwise (``--start``): fixed, so a
#: run does not depend on the day it is run (a Monday, nine in the morning)
DEFAULT_START = datetime(2026, 1, 5, 9, 0)

#: called with (time before, time after) for each advance, or each step of one
ClockObserver = Callable[[float, float], None]

_SLACK = 1e-9  #: seconds: a remainder this much over a step is still one step


@dataclass
class Clock:
    """Seconds of simulated time since the simulation started."""

    time: float = 0.0
    _observers: dict[ClockObserver, float | None] = field(
        default_factory=dict, init=False, repr=False, compare=False)

    def now(self) -> float:
        return self.time

    def observe(self, observer: ClockObserver, *, step: float | None = None) -> None:
        """Call ``observer(before, after)`` after every advance, in order of registration.

        ``step`` (seconds): cut longer advances into steps of at most this much, each
        observed (by every observer); None: observe each advance whole.
        """
        if step is not None and not step > 0:
            raise ValueError("an observer's step is a positive number of seconds")
        self._observers[observer] = step

    def forget(self, observer: ClockObserver) -> None:
        """Stop calling ``observer`` (one that was never registered is ignored)."""
        self._observers.pop(observer, None)

    def advance(self, seconds: float, *, cancel: CancelToken | None = None) -> float:
        """Let ``seconds`` pass; returns the new time.

        With ``cancel``, time stops passing at the end of the step in which the token was
        cancelled (none passes when it already was; with no observer asking for steps,
        the advance is one step): a long
        action that is cancelled lasts only until then.
        """
        if seconds < 0:
            raise ValueError("time cannot run backwards")
        steps = [step for step in self._observers.values() if step is not None]
        step = min(steps) if steps else None
        target = self.time + seconds
        while not (cancel is not None and cancel.cancelled):
            if step is None or target - self.time <= step + _SLACK:
                self._pass(target)
                break
            self._pass(self.time + step)
        return self.time

    def _pass(self, after: float) -> None:
        before, self.time = self.time, after
        for observer in list(self._observers):
            observer(before, after)


def start_time(text: str) -> datetime:
    """A run's start as a person writes it: ``2026-11-29 14:30`` (or ``2026-11-29T14:30``,
    seconds allowed, or a date alone for midnight); ``ValueError`` says how to write it."""
    try:
        when = datetime.fromisoformat(text.strip())
    except ValueError:
        raise ValueError(f"'{text}' is not a date and time; write it as YYYY-MM-DD HH:MM, "
                         "e.g. 2026-11-29 14:30") from None
    if when.tzinfo is not None:
        raise ValueError(f"'{text}' names a time zone; give the home's local time, "
                         "e.g. 2026-11-29 14:30")
    return when
