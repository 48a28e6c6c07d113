"""What the executive reports about a task: per step, and as a whole."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["StepReport", "TaskReport"]


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


@dataclass
class TaskReport:
    """How a task ended: success, each step, everything said, and simulated duration."""

    success: bool
    steps: list[StepReport] = field(default_factory=list)
    speech: list[str] = field(default_factory=list)
    sim_time: float = 0.0
    reason: str = ""

    def __bool__(self) -> bool:
        return self.success

    def to_dict(self) -> dict[str, Any]:
        return {"success": self.success, "steps": [step.to_dict() for step in self.steps],
                "speech": list(self.speech), "sim_time": round(self.sim_time, 2)}
