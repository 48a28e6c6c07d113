"""``Task`` and ``Step``: what every engine hands to the executive.

A step names a skill and its arguments, flat, as the GPSR parser prints them:
``Step("find_object", {"object": "fruit", "room": "kitchen"})``. The skills and
their arguments are listed in ``homebot.skills.catalogue``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["Step", "Task"]


@dataclass(frozen=True, slots=True)
class Step:
    """One skill call: the skill's name and its keyword arguments."""

    skill: str
    args: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """``{"skill": NAME, **args}``, the form parsers and task files use."""
        return {"skill": self.skill, **self.args}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Step:
        """The inverse of ``to_dict``."""
        args = {key: value for key, value in data.items() if key != "skill"}
        return cls(skill=str(data["skill"]), args=args)

    def __str__(self) -> str:
        arguments = ", ".join(f"{key}={value!r}" for key, value in self.args.items())
        return f"{self.skill}({arguments})"


@dataclass(frozen=True, slots=True)
class Task:
    """An ordered list of steps with the words it came from, if any."""

    steps: tuple[Step, ...]
    description: str = ""

    def to_dicts(self) -> list[dict[str, Any]]:
        return [step.to_dict() for step in self.steps]
