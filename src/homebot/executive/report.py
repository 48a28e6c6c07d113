"""The one run report every engine returns, its JSON form, and its one printer.

A GPSR task, an HTN goal, a Golog program and a SitLog dialogue all end in a
``RunReport``: success, each step the executive ran, everything said, simulated
duration and why it failed. What only one engine has (the HTN plans and
operators, Golog's program trace, SitLog's situations visited) is its ``detail``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Generic, Protocol, TypeVar

from rich.console import Console
from rich.markup import escape

from homebot.text import terminal_safe

__all__ = ["RunDetail", "RunReport", "StepReport", "print_report"]


@dataclass(frozen=True, slots=True)
class StepReport:
    """How one step ended."""

    skill: str
    args: dict[str, Any]
    status: str
    error: str | None
    message: str = ""
    recoveries: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {"skill": self.skill, "args": self.args, "status": self.status,
                "error": self.error}

    def line(self) -> str:
        """The step for a person to read (rich markup): status, call, error, recoveries."""
        colour = "green" if self.status == "verified" else (
            "yellow" if self.status == "finished" else "red")
        args = escape(", ".join(f"{key}={value}" for key, value in self.args.items()))
        error = f" ({escape(self.error)})" if self.error else ""
        recovered = f" after {escape(', '.join(self.recoveries))}" if self.recoveries else ""
        return f"[{colour}]{self.status:9}[/] {self.skill}({args}){error}{recovered}"


class RunDetail(Protocol):
    """What one engine adds to its run report."""

    def to_dict(self) -> dict[str, Any]:
        """JSON fields, merged into the report's own (``plans``, ``log``, ``history`` ...)."""
        ...

    def lines(self) -> list[str]:
        """What to show a person (rich markup), in place of the executive's step lines:
        the engine's own view of its steps (operators, actions, situations)."""
        ...


DetailT = TypeVar("DetailT", bound="RunDetail | None")


@dataclass
class RunReport(Generic[DetailT]):
    """How a run ended: success, each step, everything said, simulated duration, why not,
    and the engine's own ``detail`` (None for a plain task of steps)."""

    success: bool
    steps: list[StepReport] = field(default_factory=list)
    speech: list[str] = field(default_factory=list)
    sim_time: float = 0.0
    reason: str = ""
    detail: DetailT = None  # type: ignore[assignment]  # None is the plain task's detail

    def __bool__(self) -> bool:
        return self.success

    def to_dict(self) -> dict[str, Any]:
        """The JSON every command prints for a run (``--json``)."""
        common = {"success": self.success, "steps": [step.to_dict() for step in self.steps],
                  "speech": list(self.speech), "sim_time": round(self.sim_time, 2),
                  "reason": self.reason}
        extra = self.detail.to_dict() if self.detail is not None else {}
        return {**common, **{key: value for key, value in extra.items() if key not in common}}


def print_report(console: Console, report: RunReport[Any], *, speech: bool = True) -> None:
    """Print a run for a person: the engine's lines (else each step), what the robot said
    (unless ``speech`` is off, when it was shown as it was said) and how it ended; names and
    texts from files with their control characters escaped."""
    lines = report.detail.lines() if report.detail is not None else []
    for line in lines or [f"  {step.line()}" for step in report.steps]:
        console.print(terminal_safe(line, lines=True), highlight=False)
    if speech:
        for text in report.speech:
            console.print(f"  [cyan]robot:[/] {escape(terminal_safe(text))}", highlight=False)
    verdict = "[green]success[/]" if report.success else (
        f"[red]failed[/]: {escape(terminal_safe(report.reason))}")
    # a pure simulation of a program (no robot) takes no simulated time to speak of
    took = f" in {report.sim_time:.1f} s simulated" if report.sim_time else ""
    console.print(f"  {verdict}{took}", highlight=False)
