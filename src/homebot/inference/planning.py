"""Plan inference (§8.3): depth-first search over move, take, deliver and search with pruning."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass

from homebot.task import Step

__all__ = ["HAND", "USER", "ActionModel", "BasicAction", "Carry", "Plan", "plan_carries"]

#: The source of a product the robot already holds.
HAND = "hand"
#: The destination (and location) of the client.
USER = "user"


@dataclass(frozen=True, slots=True)
class Carry:
    """Bring ``product`` from ``source`` (a shelf or ``hand``) to ``destination`` (shelf or user).

    ``assumed`` marks a source that only the diagnosis puts it on: the robot
    must look there (``search``) before it takes it.
    """

    product: str
    source: str
    destination: str
    assumed: bool = False


@dataclass(frozen=True, slots=True, order=True)
class BasicAction:
    """``move(s)``, ``search(user)``, ``search(o)``, ``take(o)`` or ``deliver(o)``.

    ``where`` is the move's goal, or the place where the action happens.
    """

    kind: str
    where: str
    product: str = ""

    def __str__(self) -> str:
        if self.kind == "move":
            return f"move({self.where})"
        if self.kind == "search_user":
            return "search(user)"
        return f"{self.kind}({self.product})"


@dataclass(frozen=True, slots=True)
class ActionModel:
    """Time (seconds) and success probability of each basic action (§8.2's parameters)."""

    speed: float = 0.5
    turn: float = 1.0
    take_time: float = 12.0
    deliver_time: float = 9.0
    search_time: float = 2.0
    move_success: float = 0.98
    take_success: float = 0.9
    deliver_success: float = 0.95
    search_success: float = 0.95

    def cost(self, action: BasicAction, here: str,
             distance: Callable[[str, str], float]) -> tuple[float, float]:
        """``(seconds, probability)`` of ``action`` done from location ``here``."""
        if action.kind in ("move", "search_user"):
            return distance(here, action.where) / self.speed + self.turn, self.move_success
        if action.kind == "take":
            return self.take_time, self.take_success
        if action.kind == "deliver":
            return self.deliver_time, self.deliver_success
        return self.search_time, self.search_success


@dataclass(frozen=True, slots=True)
class Plan:
    """A list of basic actions with its total time and its probability of success."""

    actions: tuple[BasicAction, ...]
    cost: float
    probability: float
    carries: tuple[Carry, ...]

    @property
    def score(self) -> float:
        """Expected time: cost over probability (what the search minimises)."""
        return self.cost / self.probability if self.probability > 0 else math.inf

    def steps(self, place: Callable[[str], str], client: str = "operator") -> list[Step]:
        """The plan as skill steps: navigate, look, pick, place, give."""
        steps: list[Step] = []
        for action in self.actions:
            if action.kind == "move":
                steps.append(Step("navigate", {"to": place(action.where)}))
            elif action.kind == "search_user":
                steps.append(Step("navigate", {"to": client}))
            elif action.kind == "search":
                steps.append(Step("look", {"placement": place(action.where)}))
            elif action.kind == "take":
                steps.append(Step("pick", {"object": action.product}))
            elif action.where == USER:
                steps.append(Step("give", {"person": client, "object": action.product}))
            else:
                steps.append(Step("place", {"placement": place(action.where),
                                            "object": action.product}))
        return steps

    def __repr__(self) -> str:
        listed = ", ".join(str(a) for a in self.actions)
        return f"Plan([{listed}], cost={self.cost:.1f}s, p={self.probability:.2f})"


def _basic_actions(carry: Carry) -> list[BasicAction]:
    """The list of basic actions one obligation turns into (§8.3)."""
    actions: list[BasicAction] = []
    if carry.source != HAND:
        actions.append(BasicAction("move", carry.source))
        if carry.assumed:
            actions.append(BasicAction("search", carry.source, carry.product))
        actions.append(BasicAction("take", carry.source, carry.product))
    if carry.destination == USER:
        actions.append(BasicAction("search_user", USER))
    else:
        actions.append(BasicAction("move", carry.destination))
    actions.append(BasicAction("deliver", carry.destination, carry.product))
    return actions


_ORDER = {"deliver": 0, "take": 1, "search": 2, "move": 3, "search_user": 3}


@dataclass(frozen=True, slots=True)
class _Node:
    location: str
    hands: tuple[str, ...]
    remaining: frozenset[str]
    budget: tuple[tuple[BasicAction, int], ...]
    searched: frozenset[str]
    last: str


def plan_carries(carries: Iterable[Carry], here: str, distance: Callable[[str, str], float],
                 *, holding: Iterable[str] = (), hands: int = 2,
                 model: ActionModel | None = None) -> Plan | None:
    """The plan of least expected time that carries out every ``Carry``; None if none exists.

    Depth-first search from the robot's location, hands and the multiset B of
    basic actions, discarding (the paper's rules): a move or search(user) right
    after a move or search(user); a search right after a search or search(user),
    or with both hands full; a deliver of something not taken; a take with no free
    hand. Besides, each action happens where it must (take at the source, deliver
    at the destination), a take at an assumed source follows a search there, and
    branches no better than the best plan found are cut (costs only add up).
    """
    model = model or ActionModel()
    carries = tuple(carries)
    goal = {c.product: c for c in carries}
    if not carries:
        return Plan((), 0.0, 1.0, ())
    counter = Counter(a for c in carries for a in _basic_actions(c))
    held = tuple(sorted(holding))
    start = _Node(here, held, frozenset(goal), tuple(sorted(counter.items())), frozenset(), "")
    best: list[Plan] = []
    seen: dict[_Node, float] = {}

    def expand(node: _Node, actions: list[BasicAction], cost: float, probability: float) -> None:
        score = cost / probability
        if best and score >= best[0].score:
            return
        if not node.remaining:
            best[:] = [Plan(tuple(actions), cost, probability, carries)]
            return
        if seen.get(node, math.inf) <= score:
            return
        seen[node] = score
        children = []
        for action, _count in node.budget:
            if not _applicable(action, node, goal, hands):
                continue
            seconds, chance = model.cost(action, node.location, distance)
            children.append((seconds, action, chance))
        # Deliver first (it frees a hand), then take, search, move; cheaper first.
        children.sort(key=lambda child: (_ORDER[child[1].kind], child[0], child[1]))
        for seconds, action, chance in children:
            actions.append(action)
            expand(_successor(node, action), actions, cost + seconds, probability * chance)
            actions.pop()

    expand(start, [], 0.0, 1.0)
    return best[0] if best else None


def _applicable(action: BasicAction, node: _Node, goal: dict[str, Carry], hands: int) -> bool:
    kind = action.kind
    if kind in ("move", "search_user"):
        return node.last not in ("move", "search_user") and action.where != node.location
    if kind == "search":
        return (node.last not in ("search", "search_user") and len(node.hands) < hands
                and action.where == node.location)
    if kind == "take":
        return (len(node.hands) < hands and action.where == node.location
                and action.product not in node.hands
                and (not goal[action.product].assumed or action.product in node.searched))
    return action.product in node.hands and action.where == node.location


def _successor(node: _Node, action: BasicAction) -> _Node:
    budget = []
    for item, count in node.budget:
        if item == action:
            count -= 1
        if count:
            budget.append((item, count))
    location, hands, remaining = node.location, node.hands, node.remaining
    searched = node.searched
    if action.kind in ("move", "search_user"):
        location, searched = action.where, frozenset()
    elif action.kind == "search":
        searched = searched | {action.product}
    elif action.kind == "take":
        hands = tuple(sorted((*hands, action.product)))
    else:
        held = list(hands)
        held.remove(action.product)
        hands, remaining = tuple(held), remaining - {action.product}
    return _Node(location, hands, remaining, tuple(budget), searched, action.kind)
