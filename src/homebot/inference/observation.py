"""Observations ⟨s, P, Q, M⟩ of one shelf against the KB, and the obligations they raise (§7)."""

from __future__ import annotations

from dataclasses import dataclass, field

from homebot.inference.inventory import Inventory

__all__ = [
    "Notes",
    "Observation",
    "PutBack",
    "fulfil_cognitive_obligations",
    "listing",
    "observe",
]


@dataclass(frozen=True, slots=True)
class Observation:
    """What one look at a shelf showed, relative to what the KB believed just before.

    ``seen`` is P (every product on the shelf), ``missing`` is Q (products the KB
    placed here that are not seen), ``misplaced`` is M ⊆ P (products of another
    class), and ``unaccounted`` is Missing = Q − M_KB: the shelf's own products
    whose whereabouts the robot now does not know.
    """

    shelf: str
    seen: frozenset[str]
    missing: frozenset[str]
    misplaced: frozenset[str]
    unaccounted: frozenset[str]
    time: float = 0.0


@dataclass(frozen=True, slots=True)
class PutBack:
    """A task obligation: carry a misplaced product from where it is to its own shelf."""

    product: str
    source: str  #: a shelf, or ``hand`` when the robot already holds it
    destination: str

    def __str__(self) -> str:
        return f"put back the {self.product}"


@dataclass(slots=True)
class Notes:
    """What fulfilling the cognitive obligations said (to the client) and raised (to do)."""

    said: list[str] = field(default_factory=list)
    obligations: list[PutBack] = field(default_factory=list)


def listing(names: list[str], article: str = "") -> str:
    """'a, b and c' (each name after ``article``)."""
    named = [f"{article}{name}" for name in names]
    return named[0] if len(named) == 1 else ", ".join(named[:-1]) + " and " + named[-1] if (
        named) else ""


def _is(product: str) -> str:
    return "are" if product.endswith("s") else "is"


def observe(inventory: Inventory, shelf: str, labels: list[str] | set[str],
            time: float = 0.0) -> Observation:
    """Compute ⟨s, P, Q, M⟩ and Missing for a look at ``shelf`` that saw ``labels``."""
    seen = frozenset(label for label in labels if label in inventory.products)
    believed_here = inventory.believed_on(shelf)
    missing = frozenset(believed_here - seen)
    misplaced = frozenset(p for p in seen if not inventory.of_class(p, shelf))
    unaccounted = frozenset(p for p in missing if inventory.of_class(p, shelf))
    return Observation(shelf, seen, missing, misplaced, unaccounted, time)


def fulfil_cognitive_obligations(inventory: Inventory, observation: Observation) -> Notes:
    """Correct every false belief the observation shows, and say so (§7, items 1 and 2).

    1. Each product of Q is stated not to be on the shelf (an exception); the robot
       says it does not know where it is.
    2. Each product of P the KB placed elsewhere (a misplaced one in M, or one of
       the shelf's own thought to be missing) is stated to be here.
    Every product of M becomes a task obligation: put it back on its own shelf.
    """
    notes = Notes()
    shelf = observation.shelf
    where = inventory.shelf_name(shelf)
    for product in sorted(observation.missing):
        text = f"The {product} {_is(product)} not on {where}"
        if inventory.of_class(product, shelf):
            text += f"; I do not know where {'they are' if _is(product) == 'are' else 'it is'}."
        else:
            text += "."
        inventory.believe_not_at(product, shelf, text)
        notes.said.append(text)
    for product in sorted(observation.seen):
        if inventory.believed_at(product) == shelf:
            continue
        home = inventory.home(product)
        if product in observation.misplaced and home is not None:
            pronoun = "they" if _is(product) == "are" else "it"
            text = (f"The {product} {_is(product)} on {where}, but {pronoun} should be on "
                    f"{inventory.shelf_name(home)}.")
        else:
            text = f"The {product} {_is(product)} on {where} after all."
        inventory.believe_at(product, shelf, text)
        notes.said.append(text)
    for product in sorted(observation.misplaced):
        home = inventory.home(product)
        if home is not None:
            notes.obligations.append(PutBack(product, shelf, home))
    return notes
