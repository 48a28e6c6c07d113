"""How simulated people answer: scripted per world or scenario, or typed by a human."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import partial

from homebot.errors import TaskError
from homebot.files import read_typed_line
from homebot.text import fold
from homebot.world import PersonModel

__all__ = ["InteractiveResponder", "Responder", "ScriptedResponder", "normalise_question"]

Responder = Callable[[PersonModel, str], str | None]


def normalise_question(question: str) -> str:
    """Folded (``homebot.text.fold``: no case, no accents), no punctuation, single spaces:
    the key under which answers are scripted ("¿Qué comes?" is asked as "que comes")."""
    return " ".join(re.sub(r"[^\w\s']", " ", fold(question)).split())


@dataclass
class ScriptedResponder:
    """Answers from each person's ``answers`` in the world, overridden by a scenario script.

    ``script`` maps person name to {question: answer}. Everyone tells their name
    when asked and, asked for their question, asks how many rooms there are; any
    other question nobody scripted gets no answer.
    """

    script: Mapping[str, Mapping[str, str]] = field(default_factory=dict)

    def __call__(self, person: PersonModel, question: str) -> str | None:
        key = normalise_question(question)
        for answers in (self.script.get(person.name, {}), person.answers):
            for asked, answer in answers.items():
                if normalise_question(asked) == key:
                    return answer
        if key in {"what is your name", "what's your name", "who are you"}:
            return person.name
        if key == "what is your question":
            return "How many rooms are there?"
        return None


@dataclass
class InteractiveResponder:
    """A human types each person's answers at a prompt (``--interactive``)."""

    read_line: Callable[[str], str] = field(
        default_factory=lambda: partial(read_typed_line, error_type=TaskError))

    def __call__(self, person: PersonModel, question: str) -> str | None:
        try:
            answer = self.read_line(f"[{person.name} is asked] {question}\n> ").strip()
        except EOFError:
            return None
        return answer or None
