"""The console's request messages: pydantic models with a ``type`` field, and their limits.

Every body the console accepts is one of these, checked before anything acts on it: no
field beyond those named, strings and lists of bounded length, numbers finite and within
range, a step's arguments scalars or short lists of them (the guard has already refused
bodies over 64 KB or nested deeper than 8 levels). A request that does not fit is answered
422 with one line naming the field, and logged.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StringConstraints

__all__ = ["CommandRequest", "ControlRequest", "DriveRequest", "StepsRequest",
           "first_problem"]

MAX_TEXT = 500  #: characters of a command or a step's text
MAX_STEPS = 30
MAX_ARGS = 12  #: arguments of one step

Name = Annotated[str, StringConstraints(min_length=1, max_length=64)]
Text = Annotated[str, StringConstraints(max_length=MAX_TEXT)]
Number = Annotated[float, Field(allow_inf_nan=False, ge=-1e6, le=1e6)]
Whole = Annotated[int, Field(ge=-10**9, le=10**9)]
Scalar = StrictBool | Whole | Number | Text
Argument = Scalar | Annotated[list[Scalar], Field(max_length=8)]


class _Message(BaseModel):
    model_config = ConfigDict(extra="forbid")


class ControlRequest(_Message):
    """Take control of the robot, or give it back."""

    type: Literal["control"] = "control"
    action: Literal["take", "release"]


class DriveRequest(_Message):
    """Body level: a velocity (the console caps it)."""

    type: Literal["drive"] = "drive"
    vx: Annotated[float, Field(allow_inf_nan=False, ge=-100.0, le=100.0)] = 0.0
    wz: Annotated[float, Field(allow_inf_nan=False, ge=-100.0, le=100.0)] = 0.0


class CommandRequest(_Message):
    """Task level: a sentence for the robot."""

    type: Literal["command"] = "command"
    text: Annotated[str, StringConstraints(min_length=1, max_length=MAX_TEXT)]


class StepsRequest(_Message):
    """Skill and task level: skill steps, each ``{"skill": ..., argument: value, ...}``."""

    type: Literal["steps"] = "steps"
    steps: Annotated[list[Annotated[dict[Name, Argument], Field(min_length=1,
                                                                max_length=MAX_ARGS)]],
                     Field(min_length=1, max_length=MAX_STEPS)]
    description: Annotated[str, StringConstraints(max_length=200)] = ""


def first_problem(problems: Sequence[Mapping[str, Any]]) -> str:
    """One line for a rejected request: where in the body, and what is wrong there."""
    if not problems:
        return "the request does not fit its schema"
    first = problems[0]
    where = ".".join(str(part) for part in first.get("loc", ()) if part != "body") or "body"
    more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
    return f"{where[:120]}: {str(first.get('msg', 'invalid'))[:200]}{more}"
