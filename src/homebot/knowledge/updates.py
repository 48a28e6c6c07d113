"""Updates of the KB: add, remove and change classes, individuals, statements and weights.

Each update checks everything first and changes nothing when it raises
``KnowledgeError``; when it succeeds the taxonomy is coherent again and it returns what
it touched. Updates are plain data with a ``type`` field (``to_dict``/``from_dict``), so
the store can log them and replay them.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields, is_dataclass
from typing import Any, ClassVar

from homebot.errors import KnowledgeError
from homebot.knowledge.coherence import contradicting, statement_problems
from homebot.knowledge.model import (
    ANY,
    TOP,
    ClassNode,
    IndividualNode,
    Kind,
    Literal,
    Preference,
    Statement,
    Taxonomy,
    Value,
)
from homebot.knowledge.reasoner import Touched
from homebot.knowledge.terms import format_statement, parse_statement

__all__ = [
    "AddClass",
    "AddIndividual",
    "AddStatement",
    "ChangeValue",
    "ChangeWeight",
    "MoveClass",
    "MoveIndividual",
    "RemoveClass",
    "RemoveIndividual",
    "RemoveStatement",
    "Rename",
    "Update",
]

_UPDATE_TYPES: dict[str, type[Update]] = {}


class Update(ABC):
    """One change of the KB; subclasses are registered under their ``type_name``."""

    type_name: ClassVar[str] = ""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.type_name:
            _UPDATE_TYPES[cls.type_name] = cls

    @abstractmethod
    def apply(self, taxonomy: Taxonomy) -> Touched:
        """Change ``taxonomy`` and say what was touched; raise and change nothing if invalid."""

    def to_dict(self) -> dict[str, Any]:
        """Plain data: ``type`` plus the fields (statements as KB text)."""
        data: dict[str, Any] = {"type": self.type_name}
        if not is_dataclass(self):
            return data
        for item in fields(self):
            name = item.name
            value = getattr(self, name)
            if isinstance(value, Kind):
                value = value.value
            elif isinstance(value, Literal | Preference):
                value = format_statement(value)
            data[name] = value
        return data

    @staticmethod
    def from_dict(data: Mapping[str, Any]) -> Update:
        """The update described by ``to_dict`` output; ``KnowledgeError`` if malformed."""
        if not isinstance(data, Mapping) or data.get("type") not in _UPDATE_TYPES:
            known = ", ".join(sorted(_UPDATE_TYPES))
            raise KnowledgeError(f"an update needs a type, one of: {known}")
        cls = _UPDATE_TYPES[data["type"]]
        arguments = dict(data)
        del arguments["type"]
        try:
            if "kind" in arguments:
                arguments["kind"] = Kind(arguments["kind"])
            if "statement" in arguments:
                # change_weight's own weight field is the new weight; any weight parses its rule.
                weight = arguments.pop("weight", 0) if cls is not ChangeWeight else 1
                arguments["statement"] = _statement(arguments["statement"], weight, cls)
            return cls(**arguments)
        except (TypeError, ValueError) as error:
            raise KnowledgeError(f"malformed {data['type']} update: {error}") from None

    def __str__(self) -> str:
        fields = ", ".join(f"{k}={v}" for k, v in self.to_dict().items() if k != "type")
        return f"{self.type_name}({fields})"


def _statement(text: object, weight: object, cls: type[Update]) -> Statement:
    if isinstance(text, Literal | Preference):
        return text
    if not isinstance(text, str) or isinstance(weight, bool) or not isinstance(weight, int):
        raise KnowledgeError(f"{cls.type_name}: a statement is KB text with a whole-number weight")
    return parse_statement(text, weight, source=f"{cls.type_name} statement")


# -- classes ------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class AddClass(Update):
    """Add an empty class under ``mother``."""

    type_name: ClassVar[str] = "add_class"
    name: str
    mother: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        _require_new_name(taxonomy, self.name)
        taxonomy.class_node(self.mother)
        taxonomy.classes[self.name] = ClassNode(self.name, self.mother)
        return Touched(classes=frozenset({self.name}), structure=True)


@dataclass(frozen=True, kw_only=True)
class RemoveClass(Update):
    """Remove a class; its subclasses and individuals move up to its mother.

    Relations whose object is the removed class are removed too, as in the SitLog
    KB service.
    """

    type_name: ClassVar[str] = "remove_class"
    name: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        node = taxonomy.class_node(self.name)
        if node.mother is None:
            raise KnowledgeError("class 'top' cannot be removed; every KB has it")
        mother = taxonomy.classes[node.mother]
        children = taxonomy.children(self.name)
        for child in children:
            taxonomy.classes[child].mother = mother.name
        for member in node.individuals:
            taxonomy.individuals[member].class_name = mother.name
            mother.individuals.append(member)
        del taxonomy.classes[self.name]
        touched = Touched(
            classes=frozenset({self.name, *children}),
            individuals=frozenset(node.individuals),
            membership=frozenset({self.name, mother.name}),
            structure=True,
        )
        return touched | _drop_relations_to(taxonomy, self.name)


@dataclass(frozen=True, kw_only=True)
class MoveClass(Update):
    """Give a class another mother (not one of its own subclasses)."""

    type_name: ClassVar[str] = "move_class"
    name: str
    mother: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        node = taxonomy.class_node(self.name)
        taxonomy.class_node(self.mother)
        if node.mother is None:
            raise KnowledgeError("class 'top' has no mother and cannot move")
        if self.name in taxonomy.lineage(self.mother):
            raise KnowledgeError(
                f"class '{self.mother}' is '{self.name}' or below it; moving there would "
                "make a cycle"
            )
        old = node.mother
        node.mother = self.mother
        return Touched(
            classes=frozenset({self.name}),
            membership=frozenset({old, self.mother}),
            structure=True,
        )


@dataclass(frozen=True, kw_only=True)
class Rename(Update):
    """Rename a class or an individual everywhere it is named (mothers, relation objects)."""

    type_name: ClassVar[str] = "rename"
    name: str
    new_name: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        taxonomy.entity(self.name)
        if self.name == TOP:
            raise KnowledgeError("class 'top' keeps its name")
        _require_new_name(taxonomy, self.new_name)
        old, new = self.name, self.new_name
        if old in taxonomy.classes:
            taxonomy.classes = {(new if k == old else k): v for k, v in taxonomy.classes.items()}
            node = taxonomy.classes[new]
            node.name = new
            for other in taxonomy.classes.values():
                if other.mother == old:
                    other.mother = new
            for member in node.individuals:
                taxonomy.individuals[member].class_name = new
            touched = Touched(
                classes=frozenset({old, new}), membership=frozenset({old, new}), structure=True
            )
        else:
            taxonomy.individuals = {
                (new if k == old else k): v for k, v in taxonomy.individuals.items()
            }
            individual = taxonomy.individuals[new]
            individual.name = new
            members = taxonomy.classes[individual.class_name].individuals
            members[members.index(old)] = new
            touched = Touched(
                individuals=frozenset({old, new}),
                membership=frozenset({individual.class_name}),
            )
        return touched | _map_relations_to(taxonomy, old, lambda value: new)


# -- individuals ----------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class AddIndividual(Update):
    """Add an individual, without statements, to a class."""

    type_name: ClassVar[str] = "add_individual"
    name: str
    class_name: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        _require_new_name(taxonomy, self.name)
        node = taxonomy.class_node(self.class_name)
        taxonomy.individuals[self.name] = IndividualNode(self.name, self.class_name)
        node.individuals.append(self.name)
        return Touched(individuals=frozenset({self.name}), membership=frozenset({self.class_name}))


@dataclass(frozen=True, kw_only=True)
class RemoveIndividual(Update):
    """Remove an individual and the relations whose object it is."""

    type_name: ClassVar[str] = "remove_individual"
    name: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        individual = taxonomy.individual(self.name)
        taxonomy.classes[individual.class_name].individuals.remove(self.name)
        del taxonomy.individuals[self.name]
        touched = Touched(
            individuals=frozenset({self.name}),
            membership=frozenset({individual.class_name}),
        )
        return touched | _drop_relations_to(taxonomy, self.name)


@dataclass(frozen=True, kw_only=True)
class MoveIndividual(Update):
    """Make an individual a member of another class."""

    type_name: ClassVar[str] = "move_individual"
    name: str
    class_name: str

    def apply(self, taxonomy: Taxonomy) -> Touched:
        individual = taxonomy.individual(self.name)
        target = taxonomy.class_node(self.class_name)
        old = individual.class_name
        if old == self.class_name:
            raise KnowledgeError(f"'{self.name}' is already a member of '{old}'")
        taxonomy.classes[old].individuals.remove(self.name)
        target.individuals.append(self.name)
        individual.class_name = self.class_name
        return Touched(
            individuals=frozenset({self.name}), membership=frozenset({old, self.class_name})
        )


# -- statements ------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class AddStatement(Update):
    """Add a literal or conditional default to a class or individual.

    What the owner states that contradicts it in the same list is removed: the new
    statement replaces ``not(p)`` by ``p``, and an older weight of the same default.
    """

    type_name: ClassVar[str] = "add_statement"
    owner: str
    kind: Kind
    statement: Statement

    def apply(self, taxonomy: Taxonomy) -> Touched:
        entity = taxonomy.entity(self.owner)
        statements = entity.statements(_kind(self.kind))
        _require_well_formed(self.statement)
        if self.statement in statements:
            raise KnowledgeError(f"'{self.owner}' already states {self.statement}")
        kept = [s for s in statements if not contradicting(self.statement, s)]
        statements[:] = [*kept, self.statement]
        return _touched_owner(taxonomy, self.owner)

    def to_dict(self) -> dict[str, Any]:
        return _with_weight(super().to_dict(), self.statement)


@dataclass(frozen=True, kw_only=True)
class RemoveStatement(Update):
    """Remove a literal, or a conditional default whatever its weight."""

    type_name: ClassVar[str] = "remove_statement"
    owner: str
    kind: Kind
    statement: Statement

    def apply(self, taxonomy: Taxonomy) -> Touched:
        statements = taxonomy.entity(self.owner).statements(_kind(self.kind))
        position = _find(statements, self.statement, self.owner, self.kind)
        del statements[position]
        return _touched_owner(taxonomy, self.owner)

    def to_dict(self) -> dict[str, Any]:
        return _with_weight(super().to_dict(), self.statement)


@dataclass(frozen=True, kw_only=True)
class ChangeValue(Update):
    """Make ``statement`` the only thing the owner states about its name (``last_seen=>x``)."""

    type_name: ClassVar[str] = "change_value"
    owner: str
    kind: Kind
    statement: Statement

    def apply(self, taxonomy: Taxonomy) -> Touched:
        if not isinstance(self.statement, Literal):
            raise KnowledgeError("change_value takes a literal such as last_seen=>shelf_food")
        statements = taxonomy.entity(self.owner).statements(_kind(self.kind))
        _require_well_formed(self.statement)
        name = self.statement.name
        kept = [s for s in statements if not (isinstance(s, Literal) and s.name == name)]
        statements[:] = [*kept, self.statement]
        return _touched_owner(taxonomy, self.owner)


@dataclass(frozen=True, kw_only=True)
class ChangeWeight(Update):
    """Give a conditional default of the owner another weight (lower is preferred)."""

    type_name: ClassVar[str] = "change_weight"
    owner: str
    kind: Kind
    statement: Statement
    weight: int

    def apply(self, taxonomy: Taxonomy) -> Touched:
        if not isinstance(self.statement, Preference):
            raise KnowledgeError("change_weight takes a conditional default (with =>>)")
        statements = taxonomy.entity(self.owner).statements(_kind(self.kind))
        position = _find(statements, self.statement, self.owner, self.kind)
        changed = self.statement.with_weight(self.weight)
        _require_well_formed(changed)
        statements[position] = changed
        return _touched_owner(taxonomy, self.owner)


# -- helpers -----------------------------------------------------------------------------------


def _kind(kind: object) -> Kind:
    if not isinstance(kind, Kind):
        raise KnowledgeError(f"kind must be 'property' or 'relation', not {kind!r}")
    return kind


def _with_weight(data: dict[str, Any], statement: Statement) -> dict[str, Any]:
    data["weight"] = statement.weight if isinstance(statement, Preference) else 0
    return data


def _require_new_name(taxonomy: Taxonomy, name: object) -> None:
    if not isinstance(name, str) or not name or name in ("none", ANY):
        raise KnowledgeError(f"{name!r} cannot name a class or individual")
    if name in taxonomy.classes or name in taxonomy.individuals:
        raise KnowledgeError(f"'{name}' already names a class or individual")


def _require_well_formed(statement: Statement) -> None:
    if not isinstance(statement, Literal | Preference):
        raise KnowledgeError(f"{statement!r} is not a literal or conditional default")
    for _position, message in statement_problems([statement]):
        raise KnowledgeError(message)


def _find(statements: list[Statement], wanted: Statement, owner: str, kind: Kind) -> int:
    for position, statement in enumerate(statements):
        if statement == wanted or (
            isinstance(wanted, Preference)
            and isinstance(statement, Preference)
            and statement.same_rule(wanted)
        ):
            return position
    stated = ", ".join(str(s) for s in statements) or "nothing"
    raise KnowledgeError(
        f"'{owner}' does not state {wanted} in its {_kind(kind).value} list (it states {stated})"
    )


def _touched_owner(taxonomy: Taxonomy, owner: str) -> Touched:
    if owner in taxonomy.classes:
        return Touched(classes=frozenset({owner}))
    return Touched(individuals=frozenset({owner}))


def _drop_relations_to(taxonomy: Taxonomy, name: str) -> Touched:
    return _map_relations_to(taxonomy, name, lambda value: None)


def _map_relations_to(
    taxonomy: Taxonomy, name: str, replace: Callable[[Value], Value | None]
) -> Touched:
    """Rewrite (or drop, when ``replace`` gives ``None``) relations whose object is ``name``."""
    touched = Touched()
    for entity in taxonomy.entities():
        changed = False
        rewritten: list[Statement] = []
        for statement in entity.relations:
            if (
                isinstance(statement, Literal)
                and statement.value is not None
                and _names(statement.value, name)
            ):
                changed = True
                value = _replace_value(statement.value, name, replace)
                if value is None:
                    continue
                statement = statement.with_value(value)
            rewritten.append(statement)
        if changed:
            entity.relations[:] = rewritten
            touched = touched | _touched_owner(taxonomy, entity.name)
    return touched


def _names(value: Value | None, name: str) -> bool:
    if isinstance(value, tuple):
        return any(_names(item, name) for item in value)
    return value == name


def _replace_value(
    value: Value, name: str, replace: Callable[[Value], Value | None]
) -> Value | None:
    if isinstance(value, tuple):
        items = [_replace_value(item, name, replace) for item in value]
        kept = tuple(item for item in items if item is not None)
        return kept or None
    return replace(value) if value == name else value
