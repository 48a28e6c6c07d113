"""The robot's own components in simulation: modules that start, stop, crash and restart.

Ground truth for self-maintenance. A module that is running crashes after an
exponentially distributed running time (mean ``mean_time_to_failure`` seconds of
simulated time, drawn when it starts running); a start or restart fails with
``start_failure`` / ``restart_failure`` (the module is then ``failed``). A
posture component (the arm) moves between its states and never crashes. Every
change of state, and every task action's start and end, goes into ``events``
with its simulated time: the log the benchmark judges. All chance comes from
one seeded ``random.Random``.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

__all__ = ["ComponentSimulation", "SimulatedComponent"]


@dataclass(frozen=True)
class SimulatedComponent:
    """A component as the simulator sees it: kind, states, initial state, durations."""

    name: str
    kind: str  #: "module" or "posture"
    states: tuple[str, ...]
    initial: str
    durations: Mapping[str, float]


class ComponentSimulation:
    """Components in simulated time, with seeded crashes and failed restarts."""

    def __init__(self, components: list[SimulatedComponent], *, seed: int = 0,
                 mean_time_to_failure: float | Mapping[str, float] = math.inf,
                 start_failure: float = 0.0, restart_failure: float = 0.0) -> None:
        self.components = {component.name: component for component in components}
        self.rng = random.Random(seed)
        self.mean_time_to_failure = mean_time_to_failure
        self.start_failure = start_failure
        self.restart_failure = restart_failure
        self.now = 0.0
        self.state = {name: component.initial for name, component in self.components.items()}
        self.crash_at: dict[str, float] = {}
        self.events: list[dict[str, Any]] = []
        for name, state in self.state.items():
            self._record("component", component=name, state=state)
            if state == "running":
                self._schedule(name)

    # ------------------------------------------------------------------ time

    def _record(self, kind: str, **data: Any) -> None:
        self.events.append({"time": round(self.now, 6), "kind": kind, **data})

    def _mttf(self, name: str) -> float:
        mean = self.mean_time_to_failure
        return mean.get(name, math.inf) if isinstance(mean, Mapping) else mean

    def _schedule(self, name: str) -> None:
        mean = self._mttf(name)
        if math.isfinite(mean) and mean > 0:
            self.crash_at[name] = self.now + self.rng.expovariate(1.0 / mean)
        else:
            self.crash_at.pop(name, None)

    def _set(self, name: str, state: str) -> None:
        self.state[name] = state
        self._record("component", component=name, state=state)
        if state == "running":
            self._schedule(name)
        else:
            self.crash_at.pop(name, None)

    def advance(self, seconds: float, watched: Mapping[str, tuple[str, bool]] | None = None
                ) -> str | None:
        """Let up to ``seconds`` pass; crashes happen on time.

        ``watched`` maps a component to (state, must hold): when a crash breaks one
        of them, time stops at the crash and the component's name is returned.
        """
        end = self.now + seconds
        while True:
            due = [(when, name) for name, when in self.crash_at.items() if when <= end]
            if not due:
                break
            when, name = min(due)
            self.now = when
            self._set(name, "failed")
            if watched and name in watched:
                state, holds = watched[name]
                if (self.state[name] == state) != holds:
                    return name
        self.now = end
        return None

    # ------------------------------------------------------------------ operations

    def operate(self, operation: str, name: str, target: str | None = None) -> bool:
        """Do a management operation (start, stop, restart, set_posture); True if it worked.

        The operation takes its duration; a start or restart passes through
        ``starting`` and may fail. Other components may crash meanwhile.
        """
        component = self.components.get(name)
        if component is None:
            return False
        duration = component.durations.get(operation, 1.0)
        self._record("operation", operation=operation, component=name, target=target)
        if operation == "set_posture":
            if component.kind != "posture" or target not in component.states:
                return False
            self.advance(duration)
            self._set(name, target)
            return True
        if component.kind != "module":
            return False
        if operation == "stop":
            self.advance(duration)
            self._set(name, "off")
            return True
        if operation not in ("start", "restart") or (
                operation == "start" and self.state[name] != "off"):
            return False
        self._set(name, "starting")
        self.advance(duration)
        failure = self.start_failure if operation == "start" else self.restart_failure
        if self.rng.random() < failure:
            self._set(name, "failed")
            return False
        self._set(name, "running")
        return True

    def task(self, action: str, duration: float,
             watched: Mapping[str, tuple[str, bool]] | None = None) -> str | None:
        """A task action runs for ``duration``; a marker broken by a crash stops it there.

        Returns the component whose crash interrupted it, or None.
        """
        self._record("task.start", action=action)
        crashed = self.advance(duration, watched)
        self._record("task.end", action=action, interrupted=crashed)
        return crashed
