"""The RIPS test's action theory (Alg. 2): the robot's actions and the start button."""

from __future__ import annotations

from homebot.golog.build import f, ne
from homebot.golog.library import shipped_procedures
from homebot.golog.theory import Theory

__all__ = ["rips_theory"]


def rips_theory() -> Theory:
    """Fluents ``holding(x)``, ``at``, ``arm`` and ``start_button`` (``off`` until pressed).

    Actions ``grasp(x)``, ``park_arm``, ``extend_arm``, ``goto_place(p)``,
    ``introduce_yourself_and_the_team``, ``give(x, person)``, ``say(text)``;
    exogenous ``press_start_button``.
    """
    theory = Theory("rips")
    theory.fluent("holding", 1, relational=True)
    theory.fluent("at", 0, "start")
    theory.fluent("arm", 0, "parked")
    theory.fluent("start_button", 0, "off")
    theory.action("grasp", ("x",), precondition=~f("holding", "x"),
                  effects=lambda state, x: {("holding", x): True})
    theory.action("park_arm", effects=lambda state: {("arm",): "parked"})
    theory.action("extend_arm", effects=lambda state: {("arm",): "extended"})
    theory.action("goto_place", ("place",), precondition=ne(f("at"), "place"),
                  effects=lambda state, place: {("at",): place})
    theory.action("introduce_yourself_and_the_team")
    theory.action("give", ("x", "person"), precondition=f("holding", "x"),
                  effects=lambda state, x, person: {("holding", x): False})
    theory.action("say", ("text",))
    theory.action("press_start_button", exogenous=True,
                  effects=lambda state: {("start_button",): "on"})
    theory.define(*shipped_procedures("rips"))
    return theory
