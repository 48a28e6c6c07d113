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

Every skill runs through the executive's ``run_step``. A way blocked (a door
shut on it, someone standing in it) goes through the executive's recovery
protocols first (the door opened, the person asked to step aside), unless the
situation's arcs name that failure (``failed(door_closed, Data)``): then it is the
model's to handle, as every other failure is. Once the task's time budget is spent
the run stops (``RunStopped``), whatever the model expects.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from homebot.errors import DialogueError, TaskError
from homebot.executive import WAY_BLOCKED, Executive
from homebot.sitlog.evaluation import spoken
from homebot.sitlog.interpreter import RunStopped
from homebot.sitlog.terms import Struct, Term, Text, Var, deref, format_term, resolve
from homebot.skills import ErrorCode, Outcome, Status, spelled_as_world
from homebot.task import Step

if TYPE_CHECKING:
    from homebot.sitlog.interpreter import Environment

__all__ = ["SkillBody", "SkillPerception", "handled_errors", "outcome_term", "python_value",
           "skill_arguments", "term_value"]


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


_ERROR_CODES = frozenset(code.value for code in ErrorCode)


def handled_errors(expectations: Sequence[Term]) -> frozenset[ErrorCode]:
    """The error codes a situation's arcs name: ``failed(C, _)``, ``aborted(C, _)``,
    ``error(C)`` with ``C`` an atom (an arc on a variable code handles none by name)."""
    codes = set()
    for expectation in expectations:
        term = deref(expectation)
        if isinstance(term, Struct) and term.functor in ("failed", "aborted", "error"):
            code = deref(term.args[0]) if term.args else None
            if isinstance(code, str) and code in _ERROR_CODES:
                codes.add(ErrorCode(code))
    return frozenset(codes)


@dataclass
class SkillBody:
    """``say``/``screen`` actions spoken through the ``say`` skill."""

    executive: Executive

    def say(self, text: str) -> None:
        self.executive.run_step("say", {"text": text}, recover=False)


@dataclass
class SkillPerception:
    """Perceptual interpreters over the skills; ``person`` is whom speech situations address."""

    executive: Executive
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
        # a blocked way the arcs do not name, the executive's recovery mends
        recover = WAY_BLOCKED - handled_errors(expectations)
        result: Term | None = handler(resolve(request), env, recover)
        return result

    def _run(self, name: str, arguments: Mapping[str, Any], env: Environment,
             recover: frozenset[ErrorCode]) -> Outcome:
        # A model may say etagere or 'Patricia' for the world's étagère and Patrícia.
        arguments = spelled_as_world(Step(name, dict(arguments)),
                                     self.executive.context.world).args
        try:
            outcome = self.executive.run_step(name, arguments, recover=recover)
        except TaskError as error:
            raise DialogueError(f"{env.place}: {error}") from None
        if outcome.error is ErrorCode.OUT_OF_TIME:
            raise RunStopped(outcome.error.value, outcome.message)
        return outcome

    def _speech(self, request: Term, env: Environment,
                recover: frozenset[ErrorCode]) -> Term | None:
        person, question = self.person, request
        if isinstance(request, Struct) and request.functor == "ask" and request.arity == 2:
            person, question = python_value(request.args[0]), request.args[1]
        outcome = self._run("ask", {"question": spoken(question), "person": person}, env, recover)
        if not outcome:
            return None
        return Text(str(outcome.data["answer"]))

    def _vision(self, request: Term, env: Environment,
                recover: frozenset[ErrorCode]) -> Term:
        outcome = self._run("look", {"placement": python_value(request)}, env, recover)
        if not outcome:
            return Struct("error", (outcome.error.value if outcome.error else "unknown",))
        return tuple(str(label) for label in outcome.data["objects"])

    def _people(self, request: Term, env: Environment,
                recover: frozenset[ErrorCode]) -> Term:
        arguments: dict[str, Any] = {}
        if isinstance(request, Struct) and request.functor == "find" and request.arity == 2:
            arguments = {"person": {"name": python_value(request.args[0])},
                         "room": python_value(request.args[1])}
        else:
            arguments = {"person": {"name": python_value(request)}}
        outcome = self._run("find_person", arguments, env, recover)
        if not outcome:
            return Struct("error", (outcome.error.value if outcome.error else "unknown",))
        return Struct("found", (str(outcome.data["person"]),))

    def _skill(self, request: Term, env: Environment,
               recover: frozenset[ErrorCode]) -> Term:
        name, arguments = skill_arguments(request)
        return outcome_term(self._run(name, arguments, env, recover))
