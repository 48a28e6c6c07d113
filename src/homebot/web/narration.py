"""``Narrator``: each logged event as one line a person reads, as ``homebot do`` narrates.

A step's outcome is the run report's own step line (``StepReport.line``, its markup taken
off, its padding closed up): ``verified navigate(to=kitchen)``, then what the skill said;
what the robot says reads ``robot: ...``. The narrator remembers each started skill's
arguments, since a skill's status events do not repeat them. A kind it does not know reads
as its name and its fields, shortened.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from rich.text import Text

from homebot.executive.report import StepReport

__all__ = ["Narrator"]

_LONGEST = 160  #: characters of a line made of an unknown event's fields
_HIDDEN = frozenset({"n", "time", "kind", "line"})


def _said(data: Mapping[str, Any]) -> str:
    return f"robot: {data.get('text', '')}"


def _call(skill: str, args: Mapping[str, Any]) -> str:
    return f"{skill}({', '.join(f'{key}={value}' for key, value in args.items())})"


def _task_end(data: Mapping[str, Any]) -> str:
    return "task done" if data.get("success") else f"task failed: {data.get('reason', '')}"


def _blocked(data: Mapping[str, Any]) -> str:
    return f"world: the way through the {data.get('door')} is blocked ({data.get('blocker')})"


def _path(data: Mapping[str, Any]) -> str:
    return f"planned a path through {len(data.get('points') or [])} points"


_PLAIN: dict[str, Callable[[Mapping[str, Any]], str]] = {
    "speech": _said,
    "console.reply": _said,
    "sim.speech": lambda data: f"heard in the room: {data.get('text', '')}",
    "task.start": lambda data: f"task: {data.get('description', '')}",
    "task.end": _task_end,
    "sim.blocked": _blocked,
    "robot.blocked": _blocked,
    "robot.path": _path,
    "recovery": lambda data: f"recovery protocol for {data.get('error')}",
    "console.estop": lambda data: "emergency stop pressed",
    "console.estop_released": lambda data: "emergency stop released",
    "console.preempted": lambda data: f"stopped: {data.get('reason') or 'preempted'}",
    "console.error": lambda data: f"the console's task failed: {data.get('error')}",
}


class Narrator:
    """Lines for one run's events, in the order they were logged."""

    def __init__(self) -> None:
        self._args: dict[str, dict[str, Any]] = {}  #: each started skill's arguments

    def line(self, kind: str, data: Mapping[str, Any]) -> str:
        """The event of ``kind`` with fields ``data`` as one line of plain text."""
        if kind == "skill.start":
            skill, args = str(data.get("skill")), dict(data.get("args") or {})
            self._args[skill] = args
            return f"▶ {_call(skill, args)}"
        if kind == "skill.status":
            skill = str(data.get("skill"))
            error = data.get("error")
            step = StepReport(skill, self._args.get(skill, {}), str(data.get("status")),
                              None if error is None else str(error))
            said = data.get("message") or ""
            return " ".join(Text.from_markup(step.line()).plain.split()) + (
                f" — {said}" if said else "")
        plain = _PLAIN.get(kind)
        if plain is not None:
            return plain(data)
        fields = ", ".join(f"{key}={value}" for key, value in data.items()
                           if key not in _HIDDEN)
        text = f"{kind}: {fields}" if fields else kind
        return text if len(text) <= _LONGEST else text[:_LONGEST - 1] + "…"
