"""The history of a task: every transition taken, nested for embedded dialogue models."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Union

from homebot.sitlog.terms import Struct, Term, format_term, resolve

__all__ = ["History", "Transition", "last_transition", "render_globals", "render_history",
           "transitions"]


@dataclass(frozen=True, slots=True)
class Transition:
    """One situation interpreted: the expectation met and the action performed, grounded."""

    model: str
    situation: Term
    expectation: Term
    action: Term
    next: Term | None = None  #: the next situation (None after a final one)

    def term(self) -> Struct:
        """``Expectation:Action``, the transition as user functions see it."""
        return Struct(":", (self.expectation, self.action))

    def __str__(self) -> str:
        return (f"{self.model}: ({format_term(self.situation)},"
                f"{format_term(self.expectation, operand=True)}:"
                f"{format_term(self.action, operand=True)})")


#: A list of transitions in which an embedded model's transitions form a nested list.
History = list[Union[Transition, "History"]]


def transitions(history: History) -> list[Transition]:
    """Every transition, depth first, in the order they were taken."""
    result: list[Transition] = []
    for item in history:
        if isinstance(item, Transition):
            result.append(item)
        else:
            result.extend(transitions(item))
    return result


def last_transition(history: History) -> Term:
    """The last transition at the top level of ``history`` (``empty`` if none yet)."""
    for item in reversed(history):
        if isinstance(item, Transition):
            return item.term()
    return "empty"


def render_history(history: History, depth: int = 0) -> str:
    """One transition per line; an embedded model's part in brackets, indented."""
    lines: list[str] = []
    for item in history:
        if isinstance(item, Transition):
            lines.append(" " * depth + str(item))
            continue
        inner = render_history(item, depth + 1).split("\n") if item else []
        if not inner:
            continue
        inner[0] = " " * depth + "[" + inner[0].lstrip()
        inner[1:] = [" " + line for line in inner[1:]]
        inner[-1] += "]"
        lines.extend(inner)
    return "\n".join(lines)


def render_globals(values: Mapping[str, Term]) -> str:
    """``[name==>value,...]`` as SitLog prints its global variables."""
    return "[" + ",".join(f"{name}==>{format_term(resolve(value))}"
                          for name, value in values.items()) + "]"
