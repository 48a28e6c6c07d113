"""``Clock``: simulated time that only actions advance. Nothing here reads the wall clock."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Clock"]


@dataclass
class Clock:
    """Seconds of simulated time since the simulation started."""

    time: float = 0.0

    def now(self) -> float:
        return self.time

    def advance(self, seconds: float) -> float:
        """Let ``seconds`` pass; returns the new time."""
        if seconds < 0:
            raise ValueError("time cannot run backwards")
        self.time += seconds
        return self.time
