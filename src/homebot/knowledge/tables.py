"""Per-class inherited tables: facts resolved by specificity, rules in priority order.

A class's table is built from its mother's by overlaying the class's own statements, so
building every table costs one pass over the KB, and an individual's view is its class
table plus its own few statements. Keys are ``(namespace, name)`` with namespace 0 for
properties and 1 for relations.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from homebot.knowledge.coherence import contradicting
from homebot.knowledge.model import Kind, Literal, Preference, Statement, Value

__all__ = [
    "EMPTY",
    "NAMESPACES",
    "ClassTable",
    "DependencyGraph",
    "Key",
    "Resolution",
    "Rule",
    "own_levels",
    "resolve_levels",
    "sort_rules",
]

PROPERTY, RELATION = 0, 1
NAMESPACES = (PROPERTY, RELATION)
KIND_OF_NAMESPACE = (Kind.PROPERTY, Kind.RELATION)
Key = tuple[int, str]
Levels = tuple[tuple[Literal, ...], ...]


@dataclass(frozen=True, slots=True)
class Rule:
    """A conditional default as the reasoner uses it: where it comes from, which list."""

    preference: Preference
    source: str
    namespace: int
    key: Key  # (namespace, consequent name): what it concludes about

    @staticmethod
    def of(preference: Preference, source: str, namespace: int) -> Rule:
        """The rule for a preference stated by ``source`` in one of its lists."""
        return Rule(preference, source, namespace, (namespace, preference.consequent.name))

    def antecedent_keys(self) -> Iterable[Key]:
        """Every key an antecedent may be looked up under (own namespace, then the other)."""
        for antecedent in self.preference.antecedents:
            yield (self.namespace, antecedent.name)
            yield (1 - self.namespace, antecedent.name)


@dataclass(frozen=True, slots=True)
class Resolution:
    """What holds about one key of one entity.

    ``literals`` is what holds, in output order; ``decisive`` is false when only
    exclusions (``not(p=>v)``) are known; ``rule`` and ``binding`` say which
    conditional default concluded it, if one did.
    """

    literals: tuple[Literal, ...]
    decisive: bool
    rule: Rule | None = None
    binding: Value | None = None


EMPTY = Resolution((), False)


def effective(level: Iterable[Literal]) -> tuple[Literal, ...]:
    """The literals of one list, dropping those that contradict an earlier one."""
    if isinstance(level, tuple | list) and len(level) == 1:
        return tuple(level)
    kept: list[Literal] = []
    for literal in level:
        if not any(contradicting(literal, other) for other in kept):
            kept.append(literal)
    return tuple(kept)


def _exclusion(literal: Literal) -> bool:
    return literal.negated and literal.value is not None


def resolve_levels(levels: Levels) -> Resolution:
    """Specificity: the most specific level that settles the key decides it.

    ``not(p=>v)`` only excludes ``v`` and lets less specific levels speak; ``p``,
    ``not(p)`` and ``p=>w`` (``w`` not excluded) settle the key. Every exclusion up to
    the deciding level holds and is listed; as in SitLog's KB service, the first one
    below it is kept beside the value when it does not contradict it (``a=>v1`` with an
    inherited ``not(a=>v3)``), and literals are listed as stated, most specific first.
    """
    if levels and len(levels[0]) == 1:  # the common case: one literal settles it
        only = levels[0][0]
        if not _exclusion(only) and (len(levels) == 1 or not any(
                _exclusion(literal) for level in levels[1:] for literal in level)):
            return Resolution(levels[0], True)
    exclusions: list[Literal] = []
    decided: list[Literal] = []
    for level in levels:
        for literal in level:
            if _exclusion(literal):
                if literal not in exclusions:
                    exclusions.append(literal)
            elif not _excluded_by(literal, exclusions):
                decided.append(literal)
        if decided:
            break
    if not decided and not exclusions:
        return EMPTY
    values = {literal.value for literal in decided}
    shown: list[Literal] = []
    negation_shown = False
    deciding = True  # up to the level that decides, every exclusion holds and is listed
    for level in levels:
        for literal in level:
            if _exclusion(literal):
                if literal.value not in values and literal not in shown and (
                        deciding or not negation_shown):
                    shown.append(literal)
                    negation_shown = True
            elif literal in decided and literal not in shown:
                shown.append(literal)
        if deciding and any(literal in decided for literal in level):
            deciding = False
    return Resolution(tuple(shown), bool(decided))


def _excluded_by(literal: Literal, exclusions: list[Literal]) -> bool:
    if literal.negated or literal.value is None:
        return False
    return any(e.value == literal.value for e in exclusions)


def sort_rules(preferences: Iterable[tuple[Preference, int]], source: str) -> list[Rule]:
    """One entity's conditional defaults by weight; of equal weights the last listed first.

    SitLog's KB service orders one level's preferences by a permutation sort of the
    level's list reversed, so that of two equal weights the one listed last wins.
    """
    rules = [Rule.of(p, source, namespace) for p, namespace in preferences]
    rules.reverse()
    rules.sort(key=lambda rule: rule.preference.weight)
    return rules


def own_levels(
    statements_by_namespace: tuple[list[Statement], list[Statement]],
) -> tuple[dict[str, tuple[Literal, ...]], dict[str, tuple[Literal, ...]]]:
    """One entity's literals grouped by name per namespace, contradictions dropped."""
    result: tuple[dict[str, tuple[Literal, ...]], dict[str, tuple[Literal, ...]]] = ({}, {})
    for namespace in NAMESPACES:
        grouped = result[namespace]
        repeated = False
        for statement in statements_by_namespace[namespace]:
            if type(statement) is Literal:
                name = statement.name
                if name in grouped:
                    grouped[name] = (*grouped[name], statement)
                    repeated = True
                else:
                    grouped[name] = (statement,)
        if repeated:
            for name, level in grouped.items():
                if len(level) > 1:
                    grouped[name] = effective(level)
    return result


class DependencyGraph:
    """Which derived keys read which keys, and the cycles among them.

    Keys that depend on each other in a cycle form a component evaluated as one unit,
    starting from the key whose first rule comes first in priority order, so that an
    answer never depends on which question was asked first.
    """

    __slots__ = ("cycles", "dependents", "order")

    def __init__(self, rules: tuple[Rule, ...]) -> None:
        order: dict[Key, int] = {}
        edges: dict[Key, list[Key]] = {}
        for rule in rules:
            key = rule.key
            if key not in order:
                order[key] = len(order)
                edges[key] = []
        dependents: dict[Key, list[Key]] = {}
        for rule in rules:
            for needed in rule.antecedent_keys():
                if needed in order:
                    edges[rule.key].append(needed)
                dependents.setdefault(needed, []).append(rule.key)
        self.order = order
        self.dependents = dependents
        self.cycles: dict[Key, tuple[Key, ...]] = {}
        for component in _strongly_connected(edges):
            if len(component) > 1 or component[0] in edges[component[0]]:
                ordered = tuple(sorted(component, key=order.__getitem__))
                for key in ordered:
                    self.cycles[key] = ordered

    def affected_by(self, keys: Iterable[Key]) -> set[Key]:
        """Every derived key whose evaluation reads one of ``keys``, transitively."""
        seen: set[Key] = set()
        stack = list(keys)
        dependents = self.dependents
        while stack:
            for dependent in dependents.get(stack.pop(), ()):
                if dependent not in seen:
                    seen.add(dependent)
                    stack.append(dependent)
        return seen


def _strongly_connected(edges: dict[Key, list[Key]]) -> list[list[Key]]:
    """Tarjan's algorithm without recursion (chains of defaults can be long)."""
    index: dict[Key, int] = {}
    low: dict[Key, int] = {}
    on_stack: set[Key] = set()
    stack: list[Key] = []
    components: list[list[Key]] = []
    for root in edges:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, child_at = work.pop()
            if child_at == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            children = edges[node]
            if child_at < len(children):
                work.append((node, child_at + 1))
                child = children[child_at]
                if child not in index:
                    work.append((child, 0))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                components.append(component)
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return components


class ClassTable:
    """Everything a class and its members inherit, resolved once."""

    __slots__ = ("_graph", "facts", "groups", "levels", "name", "rules")

    def __init__(
        self,
        name: str,
        properties: list[Statement],
        relations: list[Statement],
        mother: ClassTable | None,
    ) -> None:
        self.name = name
        own = own_levels((properties, relations))
        self.levels: tuple[dict[str, Levels], dict[str, Levels]] = ({}, {})
        self.facts: tuple[dict[str, Resolution], dict[str, Resolution]] = ({}, {})
        for namespace in NAMESPACES:
            inherited_levels = mother.levels[namespace] if mother else {}
            inherited_facts = mother.facts[namespace] if mother else {}
            own_chains = {
                literal_name: (level, *inherited_levels.get(literal_name, ()))
                for literal_name, level in own[namespace].items()
            }
            own_facts = {name: resolve_levels(chain) for name, chain in own_chains.items()}
            # Own names first (most specific first), then the inherited ones, in C.
            levels = {**own_chains, **inherited_levels}
            levels.update(own_chains)
            facts = {**own_facts, **inherited_facts}
            facts.update(own_facts)
            self.levels[namespace].update(levels)
            self.facts[namespace].update(facts)
        own_rules = sort_rules(_preferences(properties, relations), name)
        self.rules: tuple[Rule, ...] = (*own_rules, *(mother.rules if mother else ()))
        self.groups: tuple[dict[str, tuple[Rule, ...]], dict[str, tuple[Rule, ...]]] = (
            group_rules(own_rules, mother.groups if mother else ({}, {}))
        )
        self._graph: DependencyGraph | None = None

    @property
    def graph(self) -> DependencyGraph:
        """The dependency graph of the class's rules (built on first use)."""
        if self._graph is None:
            self._graph = DependencyGraph(self.rules)
        return self._graph


def group_rules(
    own_rules: list[Rule], inherited: tuple[dict[str, tuple[Rule, ...]], ...]
) -> tuple[dict[str, tuple[Rule, ...]], dict[str, tuple[Rule, ...]]]:
    """Rules grouped by the key they conclude about; own rules before inherited ones."""
    groups: tuple[dict[str, tuple[Rule, ...]], dict[str, tuple[Rule, ...]]] = (
        dict(inherited[PROPERTY]),
        dict(inherited[RELATION]),
    )
    own_grouped: dict[Key, list[Rule]] = {}
    for rule in own_rules:
        own_grouped.setdefault(rule.key, []).append(rule)
    for (namespace, name), rules in own_grouped.items():
        groups[namespace][name] = (*rules, *inherited[namespace].get(name, ()))
    return groups


def _preferences(
    properties: list[Statement], relations: list[Statement]
) -> list[tuple[Preference, int]]:
    found = [(s, PROPERTY) for s in properties if isinstance(s, Preference)]
    found.extend((s, RELATION) for s in relations if isinstance(s, Preference))
    return found
