"""Blocksworld: blocks a, b, c on a table; ``stack(x, y)`` puts a clear block on y."""

from __future__ import annotations

from collections.abc import Mapping

from homebot.golog.build import and_, f, ne, or_
from homebot.golog.build import eq as equal
from homebot.golog.library import shipped_procedures
from homebot.golog.theory import State, Theory

__all__ = ["BLOCKS", "blocks_theory"]

BLOCKS = ("a", "b", "c")
TABLE = "table"


def blocks_theory(initial: Mapping[str, str] | None = None) -> Theory:
    """``on(x)`` is what x stands on; the default start has c on a, a and b on the table.

    ``stack(x, y)``: x and y clear (the table always is), x ≠ y, x not already on y.
    Reward: 10 with a on the table, b on a and c on b; -1 otherwise.
    """
    theory = Theory("blocks")
    theory.fluent("on", 1, TABLE)
    theory.function("clear", lambda state, block: block == TABLE or not any(
        state.get(("on", other), TABLE) == block for other in BLOCKS))
    theory.function("reward", _reward)
    theory.action("stack", ("x", "y"),
                  precondition=and_(ne("x", TABLE), ne("x", "y"), f("clear", "x"),
                                    f("clear", "y"), ne(f("on", "x"), "y"),
                                    or_(equal("y", TABLE), ne("y", TABLE))),
                  effects=lambda state, x, y: {("on", x): y})
    theory.define(*shipped_procedures("blocks"))
    start = initial if initial is not None else {"c": "a"}
    theory.initially({("on", block): below for block, below in start.items()})
    return theory


def _reward(state: State) -> float:
    tower = (state.get(("on", "a"), TABLE) == TABLE and state.get(("on", "b"), TABLE) == "a"
             and state.get(("on", "c"), TABLE) == "b")
    return 10.0 if tower else -1.0
