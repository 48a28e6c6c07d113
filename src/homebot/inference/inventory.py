"""``Inventory``: the robot's beliefs about shelves and products, kept in the non-monotonic KB."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from homebot.errors import KnowledgeError
from homebot.knowledge import (
    AddStatement,
    ChangeValue,
    Kind,
    KnowledgeBase,
    Literal,
    RemoveStatement,
    Update,
)
from homebot.knowledge.store import KnowledgeStore

__all__ = ["CUSTOMER", "ROBOT", "Inventory", "KbChange"]

#: Where a delivered product is believed to be: with the client.
CUSTOMER = "customer"
#: Where a product the robot carries is believed to be.
ROBOT = "robot"

_LOC = "loc"
_OUT = "out_of_stock"


@dataclass(frozen=True, slots=True)
class KbChange:
    """One change of belief the robot made, in words and as the KB update it ran."""

    text: str
    update: Update


class Inventory:
    """A view of a supermarket KB (``data/kb/supermarket.kb``) in the terms of §7 and §8.

    Shelves are the individuals of class ``shelf`` (with ``place``, the world's
    placement, and ``holds``, the class of product they are for); products are the
    individuals of class ``product``. Where a product is believed to be is the
    value of its ``loc`` relation: the class default, or the individual's own
    exception. Every update goes through ``KnowledgeBase.apply`` and is kept in
    ``changes``; with a ``store`` it is also saved (with ``clock()`` as its time).
    """

    def __init__(self, kb: KnowledgeBase, *, store: KnowledgeStore | None = None,
                 clock: Callable[[], float] | None = None) -> None:
        self.kb = store.kb if store is not None else kb
        self.store = store
        self.clock = clock or (lambda: 0.0)
        self.changes: list[KbChange] = []
        for needed in ("shelf", "product"):
            if needed not in self.kb.taxonomy.classes:
                raise KnowledgeError(f"a supermarket KB needs the class '{needed}'; add "
                                     f"class({needed},entity,[],[],[...]) (see supermarket.kb)")
        self.shelves: tuple[str, ...] = tuple(self.kb.class_extension("shelf"))
        self.products: tuple[str, ...] = tuple(self.kb.class_extension("product"))
        self._home = {product: self._home_shelf(product) for product in self.products}

    @classmethod
    def load(cls, spec: str = "supermarket") -> Inventory:
        """The inventory of a shipped KB name or a KB file."""
        return cls(KnowledgeBase.load(spec))

    @classmethod
    def kept_in(cls, path: str, spec: str = "supermarket",
                clock: Callable[[], float] | None = None) -> Inventory:
        """An inventory saved in the SQLite store ``path``, made from ``spec`` the first time.

        What the robot learnt in one session (what ran out, what is misplaced) is
        what it believes at the start of the next.
        """
        from pathlib import Path

        if Path(path).is_file():
            store = KnowledgeStore.open(path)
        else:
            store = KnowledgeStore.create(path, KnowledgeBase.load(spec).taxonomy,
                                          when=(clock or (lambda: 0.0))(), why=f"from {spec}")
        return cls(store.kb, store=store, clock=clock)

    # -- shelves ------------------------------------------------------------------------------

    def place(self, shelf: str) -> str:
        """The world placement of a shelf (its ``place`` property; the id if none)."""
        value = self.kb.value(shelf, "place")
        return str(value) if value not in ("unknown", "yes", "no") else shelf

    def shelf_at(self, placement: str) -> str | None:
        """The shelf whose placement is ``placement``, if any."""
        return next((s for s in self.shelves if self.place(s) == placement), None)

    def shelf_name(self, shelf: str) -> str:
        """How the robot says a shelf's name: 'the shelf of drinks'."""
        value = self.kb.value(shelf, "name")
        return str(value) if value not in ("unknown", "yes", "no") else f"the {shelf}"

    def holds(self, shelf: str) -> str:
        """The class of product a shelf is for."""
        return str(self.kb.value(shelf, "holds"))

    # -- products -----------------------------------------------------------------------------

    def home(self, product: str) -> str | None:
        """The shelf a product belongs on (the one holding its class or an ancestor)."""
        return self._home.get(product)

    def of_class(self, product: str, shelf: str) -> bool:
        """Whether ``product`` belongs on ``shelf``."""
        return self.home(product) == shelf

    def believed_at(self, product: str) -> str | None:
        """The shelf (or ``customer``) the KB places the product at; None when unknown."""
        value = self.kb.value(product, _LOC)
        return str(value) if value not in ("unknown", "yes", "no") else None

    def believed_on(self, shelf: str) -> set[str]:
        """Every product the KB believes to be on ``shelf``."""
        return {p for p in self.products if self.believed_at(p) == shelf}

    def known_not_at(self, product: str) -> set[str]:
        """Shelves the KB says the product is not on."""
        return {shelf for shelf in self.shelves
                if self.kb.value(product, f"{_LOC}=>{shelf}") == "no"
                and self.believed_at(product) != shelf}

    def out_of_stock(self, product: str) -> bool:
        return self.kb.value(product, _OUT) == "yes"

    def substitute(self, product: str) -> str | None:
        """What to offer instead of a product that ran out (its ``substitute``)."""
        value = self.kb.value(product, "substitute")
        return str(value) if value in self.products else None

    def minimum_age(self, product: str) -> int | None:
        """The age a client must have to be served the product (alcohol: 18)."""
        value = self.kb.value(product, "min_age")
        return int(value) if isinstance(value, int | float) else None

    def member(self, name: str, class_name: str) -> bool:
        return name in self.kb.class_extension(class_name)

    def behaviour(self, behaviour: str, parameter: str, default: float) -> float:
        """A behaviour's parameter (``take``'s ``time``, ``move``'s ``success``...)."""
        if behaviour not in self.kb.taxonomy.individuals:
            return default
        value = self.kb.value(behaviour, parameter)
        return float(value) if isinstance(value, int | float) else default

    # -- cognitive obligations: correct false beliefs ----------------------------------------

    def believe_at(self, product: str, where: str, text: str) -> None:
        """The product is on ``where`` (a shelf, or ``customer``)."""
        if where == self.home(product):
            self.believe_home(product, text)
            return
        self._apply(ChangeValue(owner=product, kind=Kind.RELATION,
                                statement=Literal(_LOC, where)), text)
        self._set_out_of_stock(product, False)

    def believe_home(self, product: str, text: str) -> None:
        """The product is back on its own shelf: drop every exception about where it is."""
        for statement in list(self._own_locations(product)):
            self._apply(RemoveStatement(owner=product, kind=Kind.RELATION,
                                        statement=statement), text)
            text = ""
        self._set_out_of_stock(product, False)

    def believe_not_at(self, product: str, shelf: str, text: str) -> None:
        """The product is not on ``shelf``: a negative exception (where it is, is unknown)."""
        own = list(self._own_locations(product))
        for statement in own:
            if not statement.negated:
                self._apply(RemoveStatement(owner=product, kind=Kind.RELATION,
                                            statement=statement), "")
        refuted = {str(s.value) for s in own if s.negated}
        shelves = [shelf] if shelf in refuted else [shelf, *(
            [self.home(product)] if self.home(product) not in refuted | {shelf} else [])]
        for name in shelves:
            if name is not None and name not in refuted:
                self._apply(AddStatement(owner=product, kind=Kind.RELATION,
                                         statement=Literal(_LOC, name, negated=True)), text)
                text = ""

    def believe_out_of_stock(self, product: str, text: str) -> None:
        """No shelf holds the product: the supermarket ran out of it."""
        self._set_out_of_stock(product, True, text)

    # -- helpers ------------------------------------------------------------------------------

    def _home_shelf(self, product: str) -> str | None:
        lineage = set(self.kb.classes_of_individual(product))
        return next((s for s in self.shelves if self.holds(s) in lineage), None)

    def _own_locations(self, product: str) -> list[Literal]:
        statements = self.kb.taxonomy.individual(product).relations
        return [s for s in statements if isinstance(s, Literal) and s.name == _LOC]

    def _set_out_of_stock(self, product: str, out: bool, text: str = "") -> None:
        properties = self.kb.taxonomy.individual(product).properties
        stated = Literal(_OUT) in properties
        if out and not stated:
            self._apply(AddStatement(owner=product, kind=Kind.PROPERTY,
                                     statement=Literal(_OUT)), text)
        elif stated and not out:
            self._apply(RemoveStatement(owner=product, kind=Kind.PROPERTY,
                                        statement=Literal(_OUT)), text)

    def _apply(self, update: Update, text: str) -> None:
        if self.store is not None:
            self.store.apply(update, when=self.clock(), why=text or "the robot's own action")
        else:
            self.kb.apply(update)
        self.changes.append(KbChange(text, update))
