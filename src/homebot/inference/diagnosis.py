"""Diagnosis (§8.1): the assistant's moves and placings that explain every observation so far."""

from __future__ import annotations

import random
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from homebot.inference.inventory import CUSTOMER, ROBOT, Inventory

__all__ = ["AssistantAction", "Diagnosis", "diagnose"]

#: ``("move", shelf)`` or ``("place", product)``: what the human assistant is assumed to have done.
AssistantAction = tuple[str, str]


@dataclass(frozen=True, slots=True)
class Diagnosis:
    """Where every product is (known or assumed) and the assistant's round that put it there.

    ``location`` maps each product on a shelf to that shelf; ``assumed`` holds the
    products placed on unseen shelves (hypotheses, which later looks may refute);
    ``misplaced`` the products believed (seen or assumed) on a shelf not theirs;
    ``ran_out`` the products no shelf can hold any more; ``revised`` the products
    whose assumed shelf changed since the previous diagnosis.
    """

    location: Mapping[str, str]
    assumed: frozenset[str]
    misplaced: frozenset[str]
    ran_out: frozenset[str]
    revised: frozenset[str]
    actions: tuple[AssistantAction, ...]
    unseen: tuple[str, ...] = field(default=())

    def contents(self, shelf: str) -> set[str]:
        """The products on ``shelf`` according to this diagnosis."""
        return {p for p, s in self.location.items() if s == shelf}

    def explain(self, inventory: Inventory) -> str:
        """The assistant's round in words."""
        parts: list[str] = []
        for kind, name in self.actions:
            parts.append(f"moved to {inventory.shelf_name(name)}" if kind == "move"
                         else f"placed the {name}")
        return "The assistant " + ", ".join(parts) + "." if parts else "Nothing to explain."


def diagnose(inventory: Inventory, known: Mapping[str, Collection[str]], here: str | None,
             distance: Callable[[str, str], float], *, sought: str | None = None,
             carried: Collection[str] = (), robot_moved: Mapping[str, str] | None = None,
             previous: Diagnosis | None = None, rng: random.Random | None = None) -> Diagnosis:
    """Explain the observations ``known`` (shelf → products seen there now).

    Products seen are where they were seen. A product not seen anywhere stays
    where the KB believes it when that shelf is unseen; otherwise its belief was
    refuted and it is assigned to an unseen shelf: the sought product to the
    unseen shelf nearest ``here``, the others to the shelf the previous diagnosis
    gave them if still unseen, else at random (``rng``) among the remaining unseen
    shelves. With no unseen shelf left, the supermarket ran out of it.

    Args:
        inventory: the KB view (homes, beliefs, stock).
        known: the current contents of every shelf observed so far.
        here: the shelf the robot is at (None: measure from the first shelf).
        distance: metric distance between two shelves.
        sought: the product the current take behaviour is after.
        carried: products in the robot's hands or delivered (on no shelf).
        robot_moved: product → shelf it was on before the robot moved it.
        previous: the last diagnosis, for stable hypotheses and revisions.
        rng: the seeded source of the random distribution.

    Returns:
        The diagnosis, with the assistant's assumed round.
    """
    rng = rng or random.Random(0)
    robot_moved = dict(robot_moved or {})
    unseen = [s for s in inventory.shelves if s not in known]
    location: dict[str, str] = {}
    for shelf, products in known.items():
        for product in products:
            location[product] = shelf
    refuted: list[str] = []
    ran_out: set[str] = set()
    for product in inventory.products:
        if product in location:
            continue
        belief = inventory.believed_at(product)
        if belief == CUSTOMER and product == sought:
            ran_out.add(product)  # sold: no shelf holds it any more
        if belief == CUSTOMER or product in carried:
            continue
        if belief == ROBOT:
            belief = None  # thought to be in hand, but it is not: where it is, is unknown
        if inventory.out_of_stock(product):
            ran_out.add(product)
        elif belief in unseen:
            location[product] = belief
        else:
            refuted.append(product)
    origin = here if here in inventory.shelves else (next(iter(known), None))
    by_distance = sorted(unseen, key=lambda s: (distance(origin, s) if origin else 0.0,
                                                inventory.shelves.index(s)))
    if sought in refuted:
        refuted.remove(sought)
        refuted.insert(0, sought)
    for product in refuted:
        if not by_distance:
            ran_out.add(product)
            continue
        kept = previous.location.get(product) if previous is not None else None
        if product == sought:
            location[product] = by_distance[0]
        elif kept in by_distance:
            location[product] = kept
        else:
            rest = by_distance[1:] or by_distance
            location[product] = rng.choice(rest)
    assumed = frozenset(p for p, s in location.items() if s in unseen)
    misplaced = frozenset(p for p, s in location.items() if not inventory.of_class(p, s))
    revised = frozenset(
        p for p in assumed if previous is not None and p in previous.assumed
        and previous.location.get(p) != location[p])
    arranged = dict(location)
    arranged.update(robot_moved)
    actions = _assistant_round(inventory, arranged, list(known), distance)
    return Diagnosis(location, assumed, misplaced, frozenset(ran_out), revised, actions,
                     tuple(unseen))


def _assistant_round(inventory: Inventory, arranged: Mapping[str, str], first: list[str],
                     distance: Callable[[str, str], float]) -> tuple[AssistantAction, ...]:
    """The assistant's single round: from the first shelf seen, nearest shelf next."""
    to_visit = [s for s in inventory.shelves if any(v == s for v in arranged.values())]
    if not to_visit:
        return ()
    current = next((s for s in first if s in to_visit), to_visit[0])
    actions: list[AssistantAction] = []
    while to_visit:
        to_visit.remove(current)
        actions.append(("move", current))
        actions.extend(("place", p) for p in inventory.products if arranged.get(p) == current)
        if to_visit:
            current = min(to_visit, key=lambda s: (distance(current, s),
                                                   inventory.shelves.index(s)))
    return tuple(actions)
