"""Perceptual interpreters and the robot's output: what a situation hears, sees and says.

A perceptual interpreter receives the situation's type, its ``input`` (the question
to ask, the placement to look at, the skill to run) and the expectations (top
down), and returns the datum perceived (bottom up), which the interpreter then
matches against the expectations. ``ScriptedPerception`` reads data from a list or
a prompt; ``homebot.sitlog.robot`` feeds them from the skills' outcomes.
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

from homebot.errors import DialogueError
from homebot.sitlog.terms import Term, deref, parse_term
from homebot.text import fold

if TYPE_CHECKING:
    from homebot.sitlog.interpreter import Environment

__all__ = ["Body", "Perception", "RecordingBody", "ScriptedPerception", "utterance_term"]


class Perception(Protocol):
    """Delivers what a grounded situation perceived (None: nothing was perceived)."""

    def perceive(self, kind: str, request: Term | None, expectations: Sequence[Term],
                 env: Environment) -> Term | None:
        """The datum for a situation of type ``kind``; ``request`` is its evaluated ``input``."""


class Body(Protocol):
    """What the interpreter's basic actions (``say``, ``screen``) do with the robot."""

    def say(self, text: str) -> None:
        """Render ``text`` through speech (or a screen)."""


@dataclass
class RecordingBody:
    """A body that only remembers what it said (tests, ``sitlog run`` without a robot)."""

    said: list[str] = field(default_factory=list)
    echo: Callable[[str], None] | None = None

    def say(self, text: str) -> None:
        self.said.append(text)
        if self.echo is not None:
            self.echo(text)


def utterance_term(text: str, expectations: Sequence[Term] = ()) -> Term:
    """A typed or heard line as a term, read top-down against the expectations.

    SitLog notation is taken as written. Otherwise an expected atom whose words
    occur in the utterance, compared folded (``homebot.text.fold``: no case, no accents),
    is what was meant ("Yes, Golem, please." meets ``yes``, "jose" meets ``josé``),
    the first such in the arcs' order; failing that, the words become one atom.
    """
    stripped = unicodedata.normalize("NFC", text.strip()).rstrip(".")
    try:
        return parse_term(stripped, "<input>")
    except DialogueError:
        pass
    words = re.sub(r"[^\w\s']", " ", stripped.lower()).split()
    folded = [fold(word) for word in words]  # "Jose" meets the expectation josé
    for expectation in expectations:
        expected = deref(expectation)
        if isinstance(expected, str) and expected and _contains(folded,
                                                                fold(expected).split()):
            return expected
    return " ".join(words)


def _contains(words: list[str], phrase: list[str]) -> bool:
    size = len(phrase)
    return any(words[i:i + size] == phrase for i in range(len(words) - size + 1))


@dataclass
class ScriptedPerception:
    """Every datum comes from a list of lines (or terms), in order, whatever the type.

    ``read_line`` (e.g. ``input``) is asked once the list is used up; without it a
    run that needs more input stops with ``DialogueError``.
    """

    inputs: Iterable[str | Term] = ()
    read_line: Callable[[str], str] | None = None
    show: Callable[[str], None] | None = None  #: shown each situation's input (the question)
    consumed: list[Term] = field(default_factory=list)

    def __post_init__(self) -> None:
        self._pending = iter(list(self.inputs))

    def perceive(self, kind: str, request: Term | None, expectations: Sequence[Term],
                 env: Environment) -> Term | None:
        if self.show is not None and request is not None:
            from homebot.sitlog.evaluation import spoken

            self.show(f"{kind}: {spoken(request)}")
        item = next(self._pending, None)
        if item is None and self.read_line is not None:
            try:
                item = self.read_line(f"[{kind}] > ")
            except EOFError:
                item = None
        if item is None:
            raise DialogueError(f"no more input for the {kind} situation "
                                f"{env.situation_name}; give more inputs")
        datum = utterance_term(item, expectations) if isinstance(item, str) else item
        self.consumed.append(datum)
        return datum
