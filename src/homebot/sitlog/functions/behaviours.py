"""Generic user functions for behaviour dialogue models (membership, choice by a condition)."""

from __future__ import annotations

from homebot.sitlog.interpreter import Environment
from homebot.sitlog.model import UserFunction
from homebot.sitlog.terms import EMPTY, Struct, Term, resolve

__all__ = ["datum", "first", "member", "rest", "user_functions"]


def member(env: Environment, item: Term, items: Term, then: Term, otherwise: Term) -> Term:
    """``then`` if ``item`` is in the list ``items``, else ``otherwise`` (choose by a test)."""
    values = resolve(items)
    found = isinstance(values, tuple) and resolve(item) in values
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


def user_functions() -> dict[str, UserFunction]:
    return {"member": member, "datum": datum, "first": first, "rest": rest}
