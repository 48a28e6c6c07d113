"""Listing A5's user functions f, g and h of the paper's Appendix A program."""

from __future__ import annotations

from homebot.sitlog.interpreter import Environment
from homebot.sitlog.model import UserFunction
from homebot.sitlog.terms import Term

__all__ = ["f", "g", "h", "user_functions"]


def f(env: Environment, x: Term) -> Term:
    """``ok`` when ``x`` is the local variable ``day``, else ``'not ok'``."""
    return "ok" if x == env.get("day") else "not ok"


def g(env: Environment, _: Term) -> Term:
    """The last transition in the history of the task."""
    return env.last_transition()


def h(env: Environment, x: Term, y: Term) -> Term:
    """The next situation: ``is`` when both arguments are equal, else ``rs``."""
    return "is" if x == y else "rs"


h.values = ("is", "rs")  # type: ignore[attr-defined]  # the situations h can name (diagram)


def user_functions() -> dict[str, UserFunction]:
    return {"f": f, "g": g, "h": h}
