"""The Order Cups Demo's action theory: three cups, four positions, one free (Alg. 3)."""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from typing import Any

from homebot.golog.build import and_, eq, exists, f, ne, not_
from homebot.golog.library import shipped_procedures
from homebot.golog.theory import State, Theory

__all__ = ["CUPS", "POSITIONS", "cups_theory", "minimum_moves"]

CUPS = ("red", "green", "blue")
POSITIONS = ("p1", "p2", "p3", "p4")
SORTED_REWARD = 10.0  #: reward of a situation with the cups in the goal order
MOVE_REWARD = -1.0  #: reward of every other situation: fewer moves, higher value


def cups_theory(initial: Mapping[str, str] | None = None) -> Theory:
    """The theory with ``initial`` cup positions (unknown, hence to be perceived, if None).

    Fluent ``pos(cup)``. Actions: ``move_cup(cup, from, to)`` (precondition: the
    cup is at ``from`` and no cup is at ``to``; the robot sees where every cup is
    as it moves one, even when the move fails); ``perceive_cups`` (senses every
    ``pos``); ``say(text)``; the exogenous ``person_moves_cup(cup, to)``.
    """
    theory = Theory("order_cups")
    theory.fluent("pos", 1)
    theory.function("cups", CUPS)
    theory.function("positions", POSITIONS)
    theory.function("reward_cup", _reward_cup)
    theory.action("move_cup", ("cup", "from", "to"),
                  precondition=and_(eq(f("pos", "cup"), "from"), ne("from", "to"),
                                    not_(exists("c", "cups", eq(f("pos", "c"), "to")))),
                  effects=lambda state, cup, _from, to: {("pos", cup): to},
                  senses=lambda cup, _from, to: [("pos", other) for other in CUPS],
                  description="pick a cup up and put it down at a free position; the "
                              "robot sees the table while it does")
    theory.action("person_moves_cup", ("cup", "to"), exogenous=True,
                  effects=lambda state, cup, to: {("pos", cup): to},
                  description="someone moved a cup")
    theory.action("perceive_cups", senses=lambda: [("pos", cup) for cup in CUPS],
                  description="look at the table: where each cup stands")
    theory.action("say", ("text",))
    theory.define(*shipped_procedures("order_cups"))
    if initial is not None:
        theory.initially({("pos", cup): position for cup, position in initial.items()})
    return theory


def _reward_cup(state: State, first: str, second: str, third: str) -> float:
    goal = (first, second, third)
    done = all(state.get(("pos", cup)) == position
               for cup, position in zip(goal, POSITIONS, strict=False))
    return SORTED_REWARD if done else MOVE_REWARD


def minimum_moves(initial: Mapping[str, Any], goal: tuple[str, str, str]) -> int:
    """Brute force (breadth-first search): the fewest moves from ``initial`` to ``goal``.

    ``goal`` names the cups wanted at p1, p2 and p3.
    """
    target = tuple(POSITIONS[goal.index(cup)] for cup in CUPS)
    start = tuple(initial[cup] for cup in CUPS)
    seen = {start: 0}
    queue = deque([start])
    while queue:
        here = queue.popleft()
        if here == target:
            return seen[here]
        for index in range(len(CUPS)):
            for position in POSITIONS:
                if position in here:
                    continue
                there = (*here[:index], position, *here[index + 1:])
                if there not in seen:
                    seen[there] = seen[here] + 1
                    queue.append(there)
    raise ValueError("the goal cannot be reached")
