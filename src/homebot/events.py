"""``EventLog``: every skill start, status change, speech act and belief update, timed.

Events carry the simulated time at which they happened, never the wall clock,
so the same seed gives the same log. The log is written as JSON lines.

A long-running simulation keeps its memory flat with ``keep`` (at most the last ``keep``
events stay in memory) and ``stream`` (every event is written to a file as it
happens, so nothing is lost). ``count`` and ``since`` number events from the first ever
recorded, whether or not it is still in memory.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

__all__ = ["Event", "EventLog"]


@dataclass(frozen=True, slots=True)
class Event:
    """One thing that happened: when (simulated seconds), what kind, and its data."""

    time: float
    kind: str
    data: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        return {"time": round(self.time, 3), "kind": self.kind, **self.data}


@dataclass
class EventLog:
    """An append-only list of events, timed by ``clock``; listeners see each event.

    ``keep``: keep at most the last ``keep`` events in memory (None: every event); the
    oldest are let go a tenth of ``keep`` at a time, so that recording stays cheap, and once
    that many were recorded at least nine tenths of ``keep`` stay. ``stream``: also write
    each event, as a JSON line, when it happens. ``dropped``: how many events are no longer
    in memory.
    """

    clock: Callable[[], float]
    events: list[Event] = field(default_factory=list)
    listeners: list[Callable[[Event], None]] = field(default_factory=list)
    keep: int | None = None
    stream: TextIO | None = None
    dropped: int = 0

    def record(self, kind: str, **data: Any) -> Event:
        """Append an event of ``kind`` at the current time and tell every listener."""
        event = Event(self.clock(), kind, data)
        events = self.events
        events.append(event)
        if self.stream is not None:
            self.stream.write(_line(event))
        if self.keep is not None and len(events) > self.keep:
            cut = len(events) - self.keep + self.keep // 10
            del events[:cut]
            self.dropped += cut
        for listener in self.listeners:
            listener(event)
        return event

    @property
    def count(self) -> int:
        """How many events were ever recorded (in memory or not)."""
        return self.dropped + len(self.events)

    def since(self, index: int) -> list[Event]:
        """The events recorded from number ``index`` (see ``count``) on, as far as kept."""
        return self.events[max(0, index - self.dropped):]

    def of_kind(self, kind: str) -> Iterator[Event]:
        """The events of one kind, in order."""
        return (event for event in self.events if event.kind == kind)

    def to_json_lines(self) -> str:
        return "".join(_line(event) for event in self.events)

    def write(self, target: Path | TextIO) -> None:
        """Write the log as JSON lines to a path or an open text stream."""
        if isinstance(target, Path):
            target.write_text(self.to_json_lines(), encoding="utf-8")
        else:
            target.write(self.to_json_lines())


def _line(event: Event) -> str:
    # Names print as written ("Patrícia"), not as \u escapes.
    return json.dumps(event.to_dict(), sort_keys=True, ensure_ascii=False) + "\n"
