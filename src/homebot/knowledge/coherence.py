"""Coherence of a taxonomy: a strict tree under ``top`` and well-formed statements.

Errors make a KB unusable: no ``top``, an unknown mother, a cycle, a name used twice, a
conditional default without a weight. Warnings point at statements the reasoner ignores:
an entity that contradicts itself within one list (``p`` and ``not(p)`` side by side),
where specificity cannot decide and the statement stated first wins, as in the SitLog
KB service. Updates never introduce warnings: a new statement replaces the ones of the
same entity it contradicts.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from homebot.errors import KnowledgeError
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

__all__ = [
    "Problem",
    "check",
    "contradicting",
    "entity_problems",
    "problems",
    "statement_problems",
    "warnings",
]


@dataclass(frozen=True, slots=True)
class Problem:
    """One incoherence: where it is and what is wrong.

    ``kind`` and ``position`` point at a statement of ``entity`` when the problem is
    in one; ``field`` names a part of the entity itself (``"mother"``, ``"class"``).
    """

    entity: str
    message: str
    kind: Kind | None = None
    position: int | None = None
    field: str | None = None


def check(taxonomy: Taxonomy) -> None:
    """Raise ``KnowledgeError`` describing the first problem, if any."""
    found = problems(taxonomy)
    if found:
        raise KnowledgeError(found[0].message)


def problems(taxonomy: Taxonomy) -> list[Problem]:
    """Every incoherence of the whole taxonomy, in declaration order."""
    found = list(structure_problems(taxonomy))
    for entity in taxonomy.entities():
        found.extend(entity_problems(entity))
    return found


def structure_problems(taxonomy: Taxonomy) -> Iterable[Problem]:
    """Problems of the hierarchy itself: top, mothers, cycles, names, membership."""
    classes = taxonomy.classes
    if TOP not in classes:
        yield Problem(TOP, "the KB has no class 'top'; add class(top,none,[],[],[])")
    elif classes[TOP].mother is not None:
        yield Problem(TOP, "class 'top' must have the mother 'none'", field="mother")
    for node in classes.values():
        if node.name == TOP:
            continue
        if node.mother is None:
            yield Problem(node.name, f"class '{node.name}' needs a mother class", field="mother")
        elif node.mother not in classes:
            yield Problem(
                node.name,
                f"class '{node.name}' has the mother '{node.mother}', which is not a class "
                "of this KB",
                field="mother",
            )
    yield from _cycle_problems(classes)
    for name, individual in taxonomy.individuals.items():
        if name in classes:
            yield Problem(name, f"'{name}' names both a class and an individual")
        owner = classes.get(individual.class_name)
        if owner is None:
            yield Problem(
                name,
                f"individual '{name}' belongs to '{individual.class_name}', which is not a class",
                field="class",
            )
        elif name not in owner.individuals:
            yield Problem(name, f"class '{owner.name}' does not list individual '{name}'")
    for node in classes.values():
        for member in node.individuals:
            listed = taxonomy.individuals.get(member)
            if listed is None or listed.class_name != node.name:
                yield Problem(node.name, f"class '{node.name}' lists '{member}' wrongly")


def _cycle_problems(classes: dict[str, ClassNode]) -> Iterable[Problem]:
    state: dict[str, int] = {}  # 1: on the current path, 2: reaches top
    for start in classes:
        path = []
        current: str | None = start
        while current is not None and current in classes and current not in state:
            state[current] = 1
            path.append(current)
            current = classes[current].mother
        if current is not None and state.get(current) == 1:
            yield Problem(
                current,
                f"class '{current}' is its own ancestor; the hierarchy must be a tree",
                field="mother",
            )
        for name in path:
            state[name] = 2


def warnings(taxonomy: Taxonomy) -> list[Problem]:
    """Statements the reasoner ignores because an earlier one of the same list contradicts them."""
    found = []
    for entity in taxonomy.entities():
        for kind in Kind:
            for position, message in _contradictions(entity.statements(kind)):
                found.append(
                    Problem(
                        entity.name,
                        f"'{entity.name}' {kind.value} list: {message}; the earlier one wins",
                        kind=kind,
                        position=position,
                    )
                )
    return found


def entity_problems(entity: ClassNode | IndividualNode) -> list[Problem]:
    """Malformed statements of one class or individual."""
    found = []
    for kind in Kind:
        for position, message in statement_problems(entity.statements(kind)):
            found.append(
                Problem(
                    entity.name,
                    f"'{entity.name}' {kind.value} list: {message}",
                    kind=kind,
                    position=position,
                )
            )
    return found


def statement_problems(statements: list[Statement]) -> list[tuple[int, str]]:
    """(position, message) for each malformed statement."""
    found: list[tuple[int, str]] = []
    for position, statement in enumerate(statements):
        if isinstance(statement, Preference):
            message = _preference_problem(statement)
        else:
            message = _literal_problem(statement, allow_any=False)
        if message is not None:
            found.append((position, message))
    return found


def _contradictions(statements: list[Statement]) -> list[tuple[int, str]]:
    found: list[tuple[int, str]] = []
    kept: list[Statement] = []
    for position, statement in enumerate(statements):
        clash = next((other for other in kept if contradicting(statement, other)), None)
        if clash is None:
            kept.append(statement)
        elif clash == statement:
            found.append((position, f"{statement} is stated twice"))
        elif isinstance(statement, Preference):
            found.append((position, f"{statement} repeats {clash} with another weight"))
        else:
            found.append((position, f"{statement} contradicts {clash}"))
    return found


def contradicting(statement: Statement, other: Statement) -> bool:
    """Whether two statements of one list clash: equal, opposite, or one rule twice.

    ``not(p)`` clashes with ``p`` and with every ``p=>v``; ``not(p=>v)`` only with
    ``p=>v``.
    """
    if isinstance(statement, Preference) or isinstance(other, Preference):
        return (
            isinstance(statement, Preference)
            and isinstance(other, Preference)
            and statement.same_rule(other)
        )
    if statement.name != other.name:
        return False
    if statement == other or statement == other.negation():
        return True
    bare_negation = statement.negated and statement.value is None
    other_bare_negation = other.negated and other.value is None
    if bare_negation == other_bare_negation:
        return False
    return not (statement.negated and other.negated)


#: The largest weight a store can keep (a SQLite INTEGER).
_MAX_WEIGHT = 2**63 - 1


def _preference_problem(preference: Preference) -> str | None:
    weight = preference.weight
    if isinstance(weight, bool) or not isinstance(weight, int) or not 1 <= weight <= _MAX_WEIGHT:
        return (f"the conditional default {preference} needs a whole-number weight of 1 or "
                f"more (at most {_MAX_WEIGHT})")
    for antecedent in preference.antecedents:
        message = _literal_problem(antecedent, allow_any=True)
        if message is not None:
            return message
    message = _literal_problem(preference.consequent, allow_any=True)
    if message is not None:
        return message
    if preference.consequent.captures and not any(a.captures for a in preference.antecedents):
        return (
            f"the conditional default {preference} passes '-' to its consequent but no "
            "antecedent captures a value (p=>'-')"
        )
    return None


def _literal_problem(literal: Literal, *, allow_any: bool) -> str | None:
    if not isinstance(literal.name, str) or not literal.name or literal.name == ANY:
        return f"'{literal.name}' is not a property or relation name"
    if literal.value is None:
        return None
    if literal.value == ANY and not allow_any:
        return f"{literal}: '-' (any value) belongs in conditional defaults only"
    return _value_problem(literal.value)


def _value_problem(value: Value) -> str | None:
    if isinstance(value, bool):
        return f"{value!r} is not an atom, a number or a list"
    if isinstance(value, str | int):
        return None
    if isinstance(value, float):
        return None if math.isfinite(value) else f"{value!r} is not a finite number"
    if isinstance(value, tuple):
        for item in value:
            message = _value_problem(item)
            if message is not None:
                return message
        return None
    return f"{value!r} is not an atom, a number or a list"
