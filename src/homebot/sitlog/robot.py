"""SitLog over the skill layer: perceptual interpreters fed by skill outcomes, speech by ``say``.

Situation types and what their ``input`` names:

- ``speech``: a question (text), or ``ask(Person, Question)``; the datum is the
  answer heard (a text, turned into a term by the situation's ``interpreter``).
- ``vision``: a placement; the datum is the list of objects seen on it.
- ``people``: a person's name, or ``find(Person, Room)``; the datum is
  ``found(Name)`` or ``error(Code)``.
- ``skill``: a skill call ``name([arg==>value, ...])``; the datum is
  ``verified([key==>value, ...])``, ``failed(Code, Data)`` or ``aborted(Code, Data)``.

A failed look or search is ``error(Code)``, so a dialogue model can branch on it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from homebot.errors import DialogueError, TaskError
from homebot.sitlog.evaluation import spoken
from homebot.sitlog.terms import Struct, Term, Text, Var, deref, format_term, resolve
from homebot.skills import Outcome, SkillContext, Status, skill_named, spelled_as_world
from homebot.task import Step

if TYPE_CHECKING:
    from homebot.sitlog.interpreter import Environment

__all__ = ["SkillBody", "SkillPerception", "outcome_term", "python_value", "skill_arguments",
           "term_value"]


def python_value(term: Term) -> Any:
    """A term as a plain Python value for a skill argument (atoms and texts become str)."""
    term = resolve(term)
    if isinstance(term, Text):
        return term.text
    if isinstance(term, tuple):
        return [python_value(item) for item in term]
    if isinstance(term, Var):
        return None
    if isinstance(term, Struct):
        return format_term(term)
    return term


def term_value(value: Any) -> Term:
    """Skill data as a term: str becomes an atom, mappings lists of ``key==>value``."""
    if value is None:
        return "empty"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str | int | float):
        return value
    if isinstance(value, Mapping):
        return tuple(Struct("==>", (str(k), term_value(v))) for k, v in value.items())
    if isinstance(value, list | tuple | set | frozenset):
        items = sorted(value) if isinstance(value, set | frozenset) else value
        return tuple(term_value(item) for item in items)
    return Text(str(value))


def outcome_term(outcome: Outcome) -> Term:
    """``verified(Data)``, ``failed(Code, Data)`` or ``aborted(Code, Data)``."""
    if outcome.status is Status.VERIFIED:
        return Struct("verified", (term_value(dict(outcome.data)),))
    code = outcome.error.value if outcome.error else "unknown"
    return Struct(outcome.status.value, (code, term_value(dict(outcome.data))))


def skill_arguments(call: Term) -> tuple[str, dict[str, Any]]:
    """``pick([object==>malz, hand==>left])`` as ``("pick", {"object": "malz", "hand": ...})``."""
    call = resolve(call)
    if isinstance(call, str):
        return call, {}
    if not isinstance(call, Struct) or call.arity > 1:
        raise DialogueError(f"a skill call is name([arg==>value, ...]), not {format_term(call)}")
    arguments: dict[str, Any] = {}
    pairs = deref(call.args[0]) if call.args else ()
    for pair in pairs if isinstance(pairs, tuple) else (pairs,):
        pair = deref(pair)
        if not (isinstance(pair, Struct) and pair.functor == "==>" and pair.arity == 2
                and isinstance(deref(pair.args[0]), str)):
            raise DialogueError(f"skill {call.functor}: arguments are arg==>value, not "
                                f"{format_term(pair)}")
        arguments[str(deref(pair.args[0]))] = python_value(pair.args[1])
    return call.functor, arguments


@dataclass
class SkillBody:
    """``say``/``screen`` actions spoken through the ``say`` skill."""

    context: SkillContext

    def say(self, text: str) -> None:
        skill_named("say").run(self.context, {"text": text})


@dataclass
class SkillPerception:
    """Perceptual interpreters over the skills; ``person`` is whom speech situations address."""

    context: SkillContext
    person: str | None = None

    def perceive(self, kind: str, request: Term | None, expectations: Sequence[Term],
                 env: Environment) -> Term | None:
        handler = getattr(self, f"_{kind}", None)
        if handler is None:
            raise DialogueError(f"{env.place}: no perceptual interpreter for situation type "
                                f"'{kind}' on the robot (speech, vision, people, skill)")
        if request is None:
            raise DialogueError(f"{env.place}: a {kind} situation on the robot needs input "
                                "(what to ask, look at, find or run)")
        result: Term | None = handler(resolve(request), env)
        return result

    def _run(self, name: str, arguments: Mapping[str, Any], env: Environment) -> Outcome:
        # A model may say etagere or 'Patricia' for the world's étagère and Patrícia.
        arguments = spelled_as_world(Step(name, dict(arguments)), self.context.world).args
        try:
            return skill_named(name).run(self.context, arguments)
        except TaskError as error:
            raise DialogueError(f"{env.place}: {error}") from None

    def _speech(self, request: Term, env: Environment) -> Term | None:
        person, question = self.person, request
        if isinstance(request, Struct) and request.functor == "ask" and request.arity == 2:
            person, question = python_value(request.args[0]), request.args[1]
        outcome = self._run("ask", {"question": spoken(question), "person": person}, env)
        if not outcome:
            return None
        return Text(str(outcome.data["answer"]))

    def _vision(self, request: Term, env: Environment) -> Term:
        outcome = self._run("look", {"placement": python_value(request)}, env)
        if not outcome:
            return Struct("error", (outcome.error.value if outcome.error else "unknown",))
        return tuple(str(label) for label in outcome.data["objects"])

    def _people(self, request: Term, env: Environment) -> Term:
        arguments: dict[str, Any] = {}
        if isinstance(request, Struct) and request.functor == "find" and request.arity == 2:
            arguments = {"person": {"name": python_value(request.args[0])},
                         "room": python_value(request.args[1])}
        else:
            arguments = {"person": {"name": python_value(request)}}
        outcome = self._run("find_person", arguments, env)
        if not outcome:
            return Struct("error", (outcome.error.value if outcome.error else "unknown",))
        return Struct("found", (str(outcome.data["person"]),))

    def _skill(self, request: Term, env: Environment) -> Term:
        name, arguments = skill_arguments(request)
        return outcome_term(self._run(name, arguments, env))
