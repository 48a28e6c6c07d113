"""``Narrator``: each logged event as one line a person reads, as ``homebot do`` reports.

One narration for every place a run is followed as it happens: the console's event log
(``line``, plain text) and ``homebot demo`` (``markup``, coloured on the terminal). A
step's outcome is the run report's own step line (``StepReport.line``): ``verified
navigate(to=kitchen)``, then what the skill said; what the robot says reads ``robot: ...``,
once: a speech act the skill logs (``speech``) and the sound the robot's speaker made of it
(``sim.speech``) are one utterance, whichever was logged first. The narrator remembers
each started skill's arguments, since a skill's status events do not repeat them. A kind
it does not know reads as its name and its fields, shortened.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from rich.markup import escape
from rich.text import Text

from homebot.executive.report import StepReport

__all__ = ["Narrator"]

_LONGEST = 160  #: characters of a line made of an unknown event's fields
_HIDDEN = frozenset({"n", "time", "kind", "line"})
#: the two records of the robot's words: a skill's speech act and the speaker's sound
_SPOKEN = frozenset({"speech", "sim.speech"})


def _call(skill: str, args: Mapping[str, Any]) -> str:
    return f"{skill}({', '.join(f'{key}={value}' for key, value in args.items())})"


def _task_end(data: Mapping[str, Any]) -> str:
    if data.get("success"):
        return "[green]task done[/]"
    return f"[red]task failed[/]: {escape(str(data.get('reason', '')))}"


def _blocked(data: Mapping[str, Any]) -> str:
    return (f"[magenta]world:[/] the way through the {escape(str(data.get('door')))} is "
            f"blocked ({escape(str(data.get('blocker')))})")


def _path(data: Mapping[str, Any]) -> str:
    return f"planned a path through {len(data.get('points') or [])} points"


def _replanned(data: Mapping[str, Any]) -> str:
    return "planned a new path" if data.get("found") else "[red]found no new path[/]"


# each kind's line, in rich markup (what the event names is escaped)
_MARKUP: dict[str, Callable[[Mapping[str, Any]], str]] = {
    "task.start": lambda data: f"[bold]task:[/] {escape(str(data.get('description', '')))}",
    "task.end": _task_end,
    "sim.blocked": _blocked,
    "robot.blocked": _blocked,
    "robot.path": _path,
    "robot.replan": _replanned,
    "recovery": lambda data: f"[yellow]recovery protocol for {escape(str(data.get('error')))}[/]",
    "console.estop": lambda data: "[red]emergency stop pressed[/]",
    "console.estop_released": lambda data: "emergency stop released",
    "console.preempted": lambda data: f"stopped: {escape(str(data.get('reason') or 'preempted'))}",
    "console.error": lambda data: f"[red]the console's task failed:[/] "
                                  f"{escape(str(data.get('error')))}",
}


class Narrator:
    """Lines for one run's events, in the order they were logged."""

    def __init__(self) -> None:
        self._args: dict[str, dict[str, Any]] = {}  #: each started skill's arguments
        #: the robot's latest words not yet matched with their other record: (kind, text)
        self._unmatched: tuple[str, str] | None = None

    def line(self, kind: str, data: Mapping[str, Any]) -> str | None:
        """The event of ``kind`` with fields ``data`` as one line of plain text (None: the
        event repeats the line before, as the second record of one utterance does)."""
        marked = self.markup(kind, data)
        return None if marked is None else " ".join(Text.from_markup(marked).plain.split())

    def markup(self, kind: str, data: Mapping[str, Any]) -> str | None:
        """The event's line in rich markup (None, as for ``line``)."""
        if kind in _SPOKEN:
            return self._said(kind, str(data.get("text", "")))
        if kind == "console.reply":  # the console's answer to a command it did not run
            return f"[cyan]robot:[/] {escape(str(data.get('text', '')))}"
        if kind == "skill.start":
            skill, args = str(data.get("skill")), dict(data.get("args") or {})
            self._args[skill] = args
            return f"▶ {escape(_call(skill, args))}"
        if kind == "skill.status":
            skill = str(data.get("skill"))
            error = data.get("error")
            step = StepReport(skill, self._args.get(skill, {}), str(data.get("status")),
                              None if error is None else str(error))
            said = data.get("message") or ""
            return step.line() + (f" — {escape(str(said))}" if said else "")
        known = _MARKUP.get(kind)
        if known is not None:
            return known(data)
        fields = ", ".join(f"{key}={value}" for key, value in data.items()
                           if key not in _HIDDEN)
        text = f"{kind}: {fields}" if fields else kind
        return escape(text if len(text) <= _LONGEST else text[:_LONGEST - 1] + "…")

    def _said(self, kind: str, text: str) -> str | None:
        unmatched = self._unmatched
        if unmatched is not None and unmatched[0] != kind and unmatched[1] == text:
            self._unmatched = None  # the other record of the words just narrated
            return None
        self._unmatched = (kind, text)
        return f"[cyan]robot:[/] {escape(text)}"
