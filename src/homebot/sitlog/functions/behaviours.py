"""Generic user functions for behaviour dialogue models (membership, choice by a condition)."""

from __future__ import annotations

from homebot.robot import HelpRequest
from homebot.sitlog.interpreter import Environment
from homebot.sitlog.model import UserFunction
from homebot.sitlog.terms import EMPTY, Struct, Term, resolve
from homebot.skills import SkillContext, speak
from homebot.text import fold

__all__ = ["datum", "first", "let_me_through", "member", "rest", "user_functions"]


def member(env: Environment, item: Term, items: Term, then: Term, otherwise: Term) -> Term:
    """``then`` if ``item`` is in the list ``items``, else ``otherwise`` (choose by a test).

    Atoms are compared folded (``homebot.text.fold``): ``'creme brulee'`` is in a list
    the world spells ``['crème brûlée']``.
    """
    values, wanted = resolve(items), resolve(item)
    found = isinstance(values, tuple) and (wanted in values or (isinstance(wanted, str) and any(
        isinstance(value, str) and fold(value) == fold(wanted) for value in values)))
    return then if found else otherwise




def datum(env: Environment, data: Term, key: str) -> Term:
    """The value under ``key`` in a skill's data list ``[key==>value, ...]`` (``empty``)."""
    values = resolve(data)
    for pair in values if isinstance(values, tuple) else ():
        if isinstance(pair, Struct) and pair.functor == "==>" and pair.args[0] == key:
            return pair.args[1]
    return EMPTY


def first(env: Environment, items: Term) -> Term:
    """The first element of a list (``empty`` for an empty list)."""
    values = resolve(items)
    return values[0] if isinstance(values, tuple) and values else EMPTY


def rest(env: Environment, items: Term) -> Term:
    """A list without its first element."""
    values = resolve(items)
    return values[1:] if isinstance(values, tuple) else ()


def let_me_through(env: Environment, person: Term, door: Term) -> Term:
    """Ask the person standing in a doorway to step aside: ``yes`` if they did, else ``no``.

    Works through the Robot port of the skill context the program runs with (the
    application itself, or its ``context``).
    """
    context = env.application
    context = context if isinstance(context, SkillContext) else getattr(context, "context", None)
    if not isinstance(context, SkillContext) or not isinstance(person, str):
        return "no"
    speak(context, f"Excuse me, {person}, could you please let me through?")
    stepped = context.robot.request(person, HelpRequest.STEP_ASIDE, str(door))
    return "yes" if stepped else "no"


def user_functions() -> dict[str, UserFunction]:
    return {"member": member, "datum": datum, "first": first, "rest": rest,
            "let_me_through": let_me_through}
