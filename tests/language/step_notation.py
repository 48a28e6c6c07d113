"""The compact step notation of the hand-written test sets: "skill(key=value); ..."."""

from __future__ import annotations

import re
from typing import Any

_MACROS = {
    "fetch": "navigate(to={1}); find_object(object={0}, placement={1}); pick(object={0})",
    "fetchin": "navigate(to={1}); find_object(object={0}, room={1}); pick(object={0})",
    "give_me": "navigate(to=operator); give(person=operator)",
    "report": "navigate(to=operator); say(text=$result)",
    "put": "navigate(to={0}); place(placement={0})",
    "grab": "find_object(object={0}); pick(object={0})",
    "whatson": "navigate(to={0}); look(placement={0}); navigate(to=operator); say(text=$result)",
}
_MACRO = re.compile(r"@(\w+)(?:\(([^)]*)\))?")
_STEP = re.compile(r"^\s*(\w+)\((.*)\)\s*$")


def expand(notation: str) -> str:
    """Replace the @macros by the steps they stand for."""
    def replace(match: re.Match[str]) -> str:
        arguments = [part.strip() for part in (match.group(2) or "").split(",")]
        return _MACROS[match.group(1)].format(*arguments)
    return _MACRO.sub(replace, notation)


def parse_steps(notation: str) -> list[dict[str, Any]]:
    """Steps as ``{"skill": ..., **args}`` dicts from the notation."""
    steps = []
    for text in expand(notation).split(";"):
        if not text.strip():
            continue
        match = _STEP.match(text)
        if match is None:
            raise ValueError(f"bad step notation: {text!r}")
        step: dict[str, Any] = {"skill": match.group(1)}
        for argument in filter(None, (a.strip() for a in match.group(2).split(","))):
            key, _, value = argument.partition("=")
            key, value = key.strip(), value.strip()
            if key.startswith("person."):
                step.setdefault("person", {})[key.split(".", 1)[1]] = value
            elif key == "person" and value == "{}":
                step["person"] = {}
            else:
                step[key] = value
        steps.append(step)
    return steps
