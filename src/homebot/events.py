"""``EventLog``: every skill start, status change, speech act and belief update, timed.

Events carry the simulated time at which they happened, never the wall clock,
so the same seed gives the same log. The log is written as JSON lines.
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
    """An append-only list of events, timed by ``clock``; listeners see each event."""

    clock: Callable[[], float]
    events: list[Event] = field(default_factory=list)
    listeners: list[Callable[[Event], None]] = field(default_factory=list)

    def record(self, kind: str, **data: Any) -> Event:
        """Append an event of ``kind`` at the current time and tell every listener."""
        event = Event(self.clock(), kind, data)
        self.events.append(event)
        for listener in self.listeners:
            listener(event)
        return event

    def of_kind(self, kind: str) -> Iterator[Event]:
        """The events of one kind, in order."""
        return (event for event in self.events if event.kind == kind)

    def to_json_lines(self) -> str:
        # Names print as written ("Patrícia"), not as \u escapes.
        return "".join(json.dumps(event.to_dict(), sort_keys=True, ensure_ascii=False) + "\n"
                       for event in self.events)

    def write(self, target: Path | TextIO) -> None:
        """Write the log as JSON lines to a path or an open text stream."""
        if isinstance(target, Path):
            target.write_text(self.to_json_lines(), encoding="utf-8")
        else:
            target.write(self.to_json_lines())
