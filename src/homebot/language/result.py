"""``ParseResult``: what the parser makes of a command (steps, a question, or a refusal)."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

from homebot.task import Step, Task

__all__ = ["ParseResult", "ParseStatus"]


class ParseStatus(StrEnum):
    """How a parse ended."""

    OK = "ok"  #: understood; ``steps`` holds the skill sequence
    CLARIFY = "clarify"  #: something is missing or ambiguous; ``question`` asks for it
    REJECT = "reject"  #: cannot be done; ``reason`` says why


@dataclass(frozen=True, slots=True)
class ParseResult:
    """The outcome of ``parse_command``; true only when the status is ok."""

    status: ParseStatus
    text: str
    steps: list[Step] = field(default_factory=list)
    question: str | None = None
    reason: str | None = None
    about: str | None = None  #: the words of the command a question is about (see Clarification)
    options: tuple[str, ...] = ()  #: the readings a question chooses between
    assumed: str | None = None  #: a reading chosen without asking, and why (see readings.py)

    def __bool__(self) -> bool:
        return self.status is ParseStatus.OK

    def to_dict(self) -> dict[str, Any]:
        """``{"status", "steps", "question"|"reason"}`` as ``homebot parse --json`` prints."""
        data: dict[str, Any] = {"status": str(self.status),
                                "steps": [step.to_dict() for step in self.steps]}
        if self.question is not None:
            data["question"] = self.question
        if self.reason is not None:
            data["reason"] = self.reason
        if self.assumed is not None:
            data["assumed"] = self.assumed
        return data

    def to_task(self) -> Task:
        """The steps as a ``Task`` for the executive."""
        return Task(steps=tuple(self.steps), description=self.text)

    def __repr__(self) -> str:
        detail = self.question or self.reason or "; ".join(str(step) for step in self.steps)
        return f"ParseResult({self.status}: {detail})"
