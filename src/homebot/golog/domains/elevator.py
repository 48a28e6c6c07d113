"""The IndiGolog elevator: floors, call buttons lit by people (exogenous), an alarm."""

from __future__ import annotations

from collections.abc import Iterable

from homebot.golog.build import f, gt, lt, not_
from homebot.golog.library import shipped_procedures
from homebot.golog.theory import Theory

__all__ = ["elevator_theory"]


def elevator_theory(floors: int = 6, start: int = 3, lit: Iterable[int] = (2, 5)) -> Theory:
    """Fluents ``floor``, ``lit(n)``, ``alarm``, ``door_open``.

    Actions ``up``, ``down``, ``open``, ``close``, ``turnoff(n)``, ``ring``,
    ``reset_alarm``; exogenous ``call(n)`` (someone presses floor n's button)
    and ``fire`` (the alarm goes off).
    """
    theory = Theory("elevator")
    theory.fluent("floor", 0, start)
    theory.fluent("lit", 1, relational=True)
    theory.fluent("alarm", 0, relational=True)
    theory.fluent("door_open", 0, relational=True)
    theory.function("floors", tuple(range(1, floors + 1)))
    theory.action("up", precondition=lt(f("floor"), floors),
                  effects=lambda state: {("floor",): state.get(("floor",)) + 1})
    theory.action("down", precondition=gt(f("floor"), 1),
                  effects=lambda state: {("floor",): state.get(("floor",)) - 1})
    theory.action("open", effects=lambda state: {("door_open",): True})
    theory.action("close", effects=lambda state: {("door_open",): False})
    theory.action("turnoff", ("n",), precondition=f("lit", "n"),
                  effects=lambda state, n: {("lit", n): False})
    theory.action("ring", precondition=f("alarm"))
    theory.action("reset_alarm", precondition=f("alarm"),
                  effects=lambda state: {("alarm",): False})
    theory.action("call", ("n",), exogenous=True, precondition=not_(f("lit", "n")),
                  effects=lambda state, n: {("lit", n): True})
    theory.action("fire", exogenous=True, effects=lambda state: {("alarm",): True})
    theory.define(*shipped_procedures("elevator"))
    theory.initially({("floor",): start, **{("lit", n): True for n in lit}})
    return theory
