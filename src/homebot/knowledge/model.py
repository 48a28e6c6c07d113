"""The knowledge base as data: literals, conditional defaults, classes and individuals."""

from __future__ import annotations

import enum
from collections.abc import Iterator
from dataclasses import dataclass, field

from homebot.errors import KnowledgeError

__all__ = [
    "ANY",
    "TOP",
    "ClassNode",
    "IndividualNode",
    "Kind",
    "Literal",
    "Preference",
    "Statement",
    "Taxonomy",
    "Value",
]

#: A value: an atom, a number, or a list of those (Prolog ``[a,b]``).
Value = str | int | float | tuple["Value", ...]

#: The paper's ``'-'``: as a whole antecedent "always"; as a value in an antecedent it
#: captures whatever value holds; as a value in a consequent it receives that value.
ANY = "-"

#: The mandatory root class.
TOP = "top"


class Kind(enum.Enum):
    """Which list of a class or individual a statement belongs to."""

    PROPERTY = "property"
    """A property of the subject (``fly``, ``size=>large``)."""
    RELATION = "relation"
    """A relation of the subject to another entity (``eat=>animals``)."""

    @property
    def other(self) -> Kind:
        """The other kind (antecedents are looked up in their own kind first, then here)."""
        return Kind.RELATION if self is Kind.PROPERTY else Kind.PROPERTY


@dataclass(frozen=True, slots=True)
class Literal:
    """An atomic statement: ``p``, ``p=>v``, ``not(p)`` or ``not(p=>v)``."""

    name: str
    value: Value | None = None
    negated: bool = False

    @property
    def has_value(self) -> bool:
        """Whether it is ``p=>v`` rather than a bare ``p``."""
        return self.value is not None

    @property
    def captures(self) -> bool:
        """Whether its value is the placeholder ``'-'``."""
        return self.value == ANY

    def negation(self) -> Literal:
        """The literal with the opposite polarity."""
        return Literal(self.name, self.value, not self.negated)

    def with_value(self, value: Value) -> Literal:
        """The same literal with ``value`` in place of its value."""
        return Literal(self.name, value, self.negated)

    def __str__(self) -> str:
        from homebot.knowledge.terms import format_literal

        return format_literal(self)

    def __repr__(self) -> str:
        return f"Literal({self})"


@dataclass(frozen=True, slots=True)
class Preference:
    """A conditional default ``Antecedents =>> Consequent`` with a weight (lower wins).

    An empty tuple of antecedents is the paper's ``'-'`` (always).
    """

    antecedents: tuple[Literal, ...]
    consequent: Literal
    weight: int

    def with_weight(self, weight: int) -> Preference:
        """The same conditional default with another weight."""
        return Preference(self.antecedents, self.consequent, weight)

    def same_rule(self, other: Preference) -> bool:
        """Whether ``other`` states the same implication, whatever its weight."""
        return self.antecedents == other.antecedents and self.consequent == other.consequent

    def __str__(self) -> str:
        from homebot.knowledge.terms import format_statement

        return format_statement(self)

    def __repr__(self) -> str:
        return f"Preference({self}, weight={self.weight})"


#: A statement in a property or relation list: a literal (weight 0) or a preference.
Statement = Literal | Preference


@dataclass(slots=True)
class ClassNode:
    """A class: its mother, its own statements and the individuals declared in it."""

    name: str
    mother: str | None
    properties: list[Statement] = field(default_factory=list)
    relations: list[Statement] = field(default_factory=list)
    individuals: list[str] = field(default_factory=list)

    def statements(self, kind: Kind) -> list[Statement]:
        """The property or relation list."""
        return self.properties if kind is Kind.PROPERTY else self.relations


@dataclass(slots=True)
class IndividualNode:
    """An individual: its class and its own statements."""

    name: str
    class_name: str
    properties: list[Statement] = field(default_factory=list)
    relations: list[Statement] = field(default_factory=list)

    def statements(self, kind: Kind) -> list[Statement]:
        """The property or relation list."""
        return self.properties if kind is Kind.PROPERTY else self.relations


Entity = ClassNode | IndividualNode


class Taxonomy:
    """The strict class hierarchy under ``top`` with its individuals, in declaration order.

    It holds data only; ``homebot.knowledge.coherence`` checks it and
    ``homebot.knowledge.updates`` changes it.
    """

    __slots__ = ("classes", "individuals")

    def __init__(self) -> None:
        self.classes: dict[str, ClassNode] = {}
        self.individuals: dict[str, IndividualNode] = {}

    # -- lookups -------------------------------------------------------------

    def entity(self, name: str) -> Entity:
        """The class or individual called ``name``; raises ``KnowledgeError`` if none."""
        found = self.classes.get(name) or self.individuals.get(name)
        if found is None:
            raise KnowledgeError(_unknown_message("class or individual", name, self.names()))
        return found

    def class_node(self, name: str) -> ClassNode:
        """The class called ``name``; raises ``KnowledgeError`` if none."""
        node = self.classes.get(name)
        if node is None:
            raise KnowledgeError(_unknown_message("class", name, list(self.classes)))
        return node

    def individual(self, name: str) -> IndividualNode:
        """The individual called ``name``; raises ``KnowledgeError`` if none."""
        node = self.individuals.get(name)
        if node is None:
            raise KnowledgeError(_unknown_message("individual", name, list(self.individuals)))
        return node

    def names(self) -> list[str]:
        """Every class and individual name."""
        return [*self.classes, *self.individuals]

    def lineage(self, class_name: str) -> list[str]:
        """``class_name`` and its ancestors up to ``top``, most specific first."""
        chain = []
        current: str | None = class_name
        while current is not None:
            chain.append(current)
            current = self.classes[current].mother
            if len(chain) > len(self.classes):
                raise KnowledgeError(f"class '{class_name}' is part of a cycle of mothers")
        return chain

    def children(self, class_name: str) -> list[str]:
        """The direct subclasses of ``class_name`` in declaration order."""
        return [node.name for node in self.classes.values() if node.mother == class_name]

    def children_map(self) -> dict[str, list[str]]:
        """Every class mapped to its direct subclasses, in declaration order."""
        result: dict[str, list[str]] = {name: [] for name in self.classes}
        for node in self.classes.values():
            if node.mother is not None and node.mother in result:
                result[node.mother].append(node.name)
        return result

    def subtree(self, class_name: str) -> list[str]:
        """``class_name`` and all classes below it, depth first in declaration order."""
        children = self.children_map()
        order: list[str] = []
        stack = [class_name]
        while stack:
            current = stack.pop()
            order.append(current)
            stack.extend(reversed(children[current]))
        return order

    def statement_count(self) -> tuple[int, int]:
        """How many literals and how many preferences the KB states."""
        literals = preferences = 0
        for entity in self.entities():
            for statement in (*entity.properties, *entity.relations):
                if isinstance(statement, Preference):
                    preferences += 1
                else:
                    literals += 1
        return literals, preferences

    def entities(self) -> Iterator[Entity]:
        """Every class, then every individual."""
        yield from self.classes.values()
        yield from self.individuals.values()

    # -- comparison ------------------------------------------------------------

    def canonical(self) -> tuple[object, ...]:
        """A hashable summary: equal for taxonomies that state the same things in order.

        Individuals are compared in the order their classes list them.
        """
        return (
            tuple(
                (c.name, c.mother, tuple(c.properties), tuple(c.relations), tuple(c.individuals))
                for c in self.classes.values()
            ),
            tuple(
                (i.name, i.class_name, tuple(i.properties), tuple(i.relations))
                for c in self.classes.values()
                for i in (self.individuals.get(name) for name in c.individuals)
                if i is not None
            ),
            len(self.individuals),
        )

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Taxonomy) and self.canonical() == other.canonical()

    __hash__ = None  # type: ignore[assignment]

    def copy(self) -> Taxonomy:
        """An independent copy (statements are immutable and shared)."""
        duplicate = Taxonomy()
        for c in self.classes.values():
            duplicate.classes[c.name] = ClassNode(
                c.name, c.mother, list(c.properties), list(c.relations), list(c.individuals)
            )
        for i in self.individuals.values():
            duplicate.individuals[i.name] = IndividualNode(
                i.name, i.class_name, list(i.properties), list(i.relations)
            )
        return duplicate

    def __repr__(self) -> str:
        literals, preferences = self.statement_count()
        return (
            f"Taxonomy({len(self.classes)} classes, {len(self.individuals)} individuals, "
            f"{literals} literals, {preferences} preferences)"
        )


def _unknown_message(what: str, name: str, known: list[str]) -> str:
    """``unknown class 'x'`` with the closest known names as a hint."""
    from homebot.text import closest_names

    name = str(name)
    close = closest_names(name, known, count=3)
    hint = f"; did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    return f"unknown {what} '{name}'{hint}"
