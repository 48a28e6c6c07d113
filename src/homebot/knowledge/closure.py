"""What holds for one class or individual: facts by specificity, then conditional defaults.

Evaluation is lazy, key by key, and memoised. A key settled by a weight-0 statement at
any level is never derived (a plain statement beats a preference). Otherwise its
conditional defaults are tried in priority order (more specific level first, then lower
weight) and the first whose antecedents all hold concludes it. Antecedents may be
concluded by other defaults (chaining); evaluation uses an explicit stack, so a chain
costs time linear in its length and never exhausts Python's recursion limit. Within a
cycle of defaults a key still being evaluated counts as unknown, and cycles are always
entered at the same key (see ``DependencyGraph``), so answers do not depend on the order
of questions.
"""

from __future__ import annotations

from homebot.knowledge.model import ANY, Literal, Statement, Value
from homebot.knowledge.tables import (
    EMPTY,
    NAMESPACES,
    ClassTable,
    DependencyGraph,
    Key,
    Resolution,
    Rule,
    group_rules,
    own_levels,
    resolve_levels,
    sort_rules,
)

__all__ = ["Closure", "antecedent_holds", "instantiate"]


class _Missing(Exception):
    """Raised inside a derivation that needs a key not evaluated yet."""

    def __init__(self, key: Key) -> None:
        super().__init__(key)
        self.key = key


class Closure:
    """The lazily evaluated theory of one entity.

    For a class, ``table`` is its own table and ``own`` is ``None``. For an individual,
    ``own`` holds its statements; when it states no conditional defaults of its own, a
    derived key none of whose inputs it overrides is taken from ``inherited`` (the class's
    closure), so most of an individual's conclusions are computed once per class.
    """

    __slots__ = (
        "_affected",
        "_entries",
        "_facts",
        "_flat",
        "_graph",
        "_groups",
        "_holding",
        "_memo",
        "_own_levels",
        "_rank",
        "inherited",
        "name",
        "rules",
        "table",
    )

    def __init__(
        self,
        name: str,
        table: ClassTable,
        own: tuple[list[Statement], list[Statement]] | None = None,
        inherited: Closure | None = None,
    ) -> None:
        self.name = name
        self.table = table
        self._memo: tuple[dict[str, Resolution], dict[str, Resolution]] = ({}, {})
        self._facts: tuple[dict[str, Resolution], dict[str, Resolution]] = ({}, {})
        self._affected: set[Key] | None = None
        self._holding: list[tuple[Literal, ...] | None] = [None, None]
        self._entries: list[list[tuple[str, tuple[Literal, ...]]] | None] = [None, None]
        self._flat: list[tuple[tuple[Literal, ...], dict[str, tuple[int, int, int]]] | None] = [
            None,
            None,
        ]
        self.inherited = inherited
        self._rank: dict[int, int] | None = None
        self._own_levels = own_levels(own) if own is not None else ({}, {})
        own_rules = []
        if own is not None and not all(
            type(s) is Literal for statements in own for s in statements
        ):
            own_rules = sort_rules(
                [
                    (statement, namespace)
                    for namespace in NAMESPACES
                    for statement in own[namespace]
                    if not isinstance(statement, Literal)
                ],
                name,
            )
        if own_rules:
            self.inherited = None
            self.rules: tuple[Rule, ...] = (*own_rules, *table.rules)
            self._groups = group_rules(own_rules, table.groups)
            self._graph: DependencyGraph | None = None
        else:
            self.rules = table.rules
            self._groups = table.groups
            self._graph = None

    # -- structure -------------------------------------------------------------------

    @property
    def graph(self) -> DependencyGraph:
        """The dependency graph of this entity's rules."""
        if self._graph is None:
            if self._groups is self.table.groups:
                self._graph = self.table.graph
            else:
                self._graph = DependencyGraph(self.rules)
        return self._graph

    def derived_keys(self) -> list[Key]:
        """Keys that some conditional default concludes about, in priority order."""
        return list(self.graph.order)

    def fact_names(self, namespace: int) -> list[str]:
        """Names stated by weight-0 statements, own first, then inherited."""
        own = self._own_levels[namespace]
        return [*own, *(n for n in self.table.facts[namespace] if n not in own)]

    def rules_for(self, key: Key) -> tuple[Rule, ...]:
        """The conditional defaults concluding about ``key``, in priority order."""
        return self._groups[key[0]].get(key[1], ())

    # -- facts -----------------------------------------------------------------------------

    def facts(self, namespace: int, name: str) -> Resolution:
        """What weight-0 statements settle about a key (specificity only)."""
        own = self._own_levels[namespace].get(name)
        if own is None:
            return self.table.facts[namespace].get(name, EMPTY)
        cache = self._facts[namespace]
        found = cache.get(name)
        if found is None:
            found = resolve_levels((own, *self.table.levels[namespace].get(name, ())))
            cache[name] = found
        return found

    # -- evaluation ----------------------------------------------------------------------

    def resolve(self, namespace: int, name: str) -> Resolution:
        """What holds about ``name`` in ``namespace``, conditional defaults included."""
        found = self._memo[namespace].get(name)
        if found is not None:
            return found
        facts = self.facts(namespace, name)
        if facts.decisive or name not in self._groups[namespace]:
            self._memo[namespace][name] = facts
            return facts
        key = (namespace, name)
        reused = self._reused(key)
        if reused is None:
            try:  # most keys need nothing that is not evaluated yet
                reused = self._derive(key, set())
            except _Missing:
                self._evaluate(key)
                return self._memo[namespace][name]
        self._memo[namespace][name] = reused
        return reused

    def holding(self, namespace: int) -> tuple[Literal, ...]:
        """Everything that holds in one namespace: stated names first, then derived ones."""
        found = self._holding[namespace]
        if found is not None:
            return found
        result: list[Literal] = []
        inherited = self.inherited
        if inherited is None:
            seen: set[str] = set()
            for _, literals in self._stated(namespace, seen):
                result.extend(literals)
            for _, literals in self._derived(namespace, seen):
                result.extend(literals)
        else:
            # The class's answer, re-evaluated only where this individual makes a difference.
            own = self._own_levels[namespace]
            for name, stated in own.items():
                # what the individual states here; what its classes add, where they say it
                result.extend(x for x in self.resolve(namespace, name).literals if x in stated)
            flat, spans = inherited.flat_entries(namespace)
            facts, boundary = inherited.fact_boundary(namespace)
            affected = {k[1] for k in self._affected_keys() if k[0] == namespace}
            # A derived key this individual changes may move (derived keys are listed by
            # the default that concluded them): then the derived part is listed afresh.
            fresh = any(name in spans and spans[name][0] >= facts for name in affected)
            replaced = sorted((*spans[name], name) for name in affected
                              if name in spans and not (fresh and spans[name][0] >= facts))
            position = 0
            for _index, start, end, name in replaced:
                result.extend(flat[position:start])
                stated = own.get(name, ())
                result.extend(x for x in self.resolve(namespace, name).literals
                              if x not in stated)
                position = end
            result.extend(flat[position:boundary if fresh else len(flat)])
            if fresh:
                for _, literals in self._derived(namespace, set(self.fact_names(namespace))):
                    result.extend(literals)
        holding = tuple(result)
        self._holding[namespace] = holding
        return holding

    def entries(self, namespace: int) -> list[tuple[str, tuple[Literal, ...]]]:
        """``(name, literals)`` in the order ``holding`` lists them (for classes)."""
        cached = self._entries[namespace]
        if cached is not None:
            return cached
        seen: set[str] = set()
        result = self._stated(namespace, seen)
        result.extend(self._derived(namespace, seen))
        self._entries[namespace] = result
        return result

    def _stated(self, namespace: int, seen: set[str]) -> list[tuple[str, tuple[Literal, ...]]]:
        """The stated keys' literals where SitLog lists them: each where it is stated.

        An individual's own statements come first; what its classes add to the same key
        (an inherited ``not(p=>v)`` beside its own ``p=>w``) comes at the class's place.
        """
        result: list[tuple[str, tuple[Literal, ...]]] = []
        own = self._own_levels[namespace]
        for name, stated in own.items():
            seen.add(name)
            result.append((name, tuple(x for x in self.resolve(namespace, name).literals
                                       if x in stated)))
        for name in self.table.facts[namespace]:
            mine = own.get(name)
            if mine is None:
                seen.add(name)
                result.append((name, self.resolve(namespace, name).literals))
            else:
                rest = tuple(x for x in self.resolve(namespace, name).literals
                             if x not in mine)
                if rest:
                    result.append((name, rest))
        return result

    def fact_boundary(self, namespace: int) -> tuple[int, int]:
        """How many of ``entries`` are stated names, and where they end in ``flat_entries``."""
        facts = len(self.fact_names(namespace))
        flat, spans = self.flat_entries(namespace)
        starts = [start for index, start, _ in spans.values() if index >= facts]
        return facts, min(starts, default=len(flat))

    def _derived(self, namespace: int, seen: set[str]) -> list[tuple[str, tuple[Literal, ...]]]:
        """The derived keys not in ``seen``, ordered by the default that concluded each.

        SitLog's KB service appends conclusions as it tries the defaults in priority
        order, so a key is listed where its first firing default comes.
        """
        rank = self._rank
        if rank is None:
            rank = self._rank = {id(rule): index for index, rule in enumerate(self.rules)}
        last = len(rank)
        found: list[tuple[int, int, str, tuple[Literal, ...]]] = []
        for key_namespace, name in self.graph.order:
            if key_namespace == namespace and name not in seen:
                seen.add(name)
                resolution = self.resolve(namespace, name)
                position = last if resolution.rule is None else rank.get(id(resolution.rule),
                                                                         last)
                found.append((position, len(found), name, resolution.literals))
        found.sort()
        return [(name, literals) for _, _, name, literals in found]

    def flat_entries(
        self, namespace: int
    ) -> tuple[tuple[Literal, ...], dict[str, tuple[int, int, int]]]:
        """``holding`` as one tuple, with each name's entry number and span in it."""
        cached = self._flat[namespace]
        if cached is not None:
            return cached
        flat: list[Literal] = []
        spans: dict[str, tuple[int, int, int]] = {}
        for index, (name, literals) in enumerate(self.entries(namespace)):
            spans[name] = (index, len(flat), len(flat) + len(literals))
            flat.extend(literals)
        result = (tuple(flat), spans)
        self._flat[namespace] = result
        return result

    def _affected_keys(self) -> set[Key]:
        affected = self._affected
        if affected is None:
            own = [(ns, n) for ns in NAMESPACES for n in self._own_levels[ns]]
            affected = self._affected = self.graph.affected_by(own)
            affected.update(own)
        return affected

    def _reused(self, key: Key) -> Resolution | None:
        inherited = self.inherited
        if inherited is None or key in self._affected_keys():
            return None
        return inherited.resolve(*key)

    def _evaluate(self, start: Key) -> None:
        memo = self._memo
        cycles = self.graph.cycles
        in_progress: set[Key] = set()
        stack = [start]
        while stack:
            key = stack[-1]
            namespace, name = key
            if name in memo[namespace]:
                stack.pop()
                continue
            if key not in in_progress:
                cycle = cycles.get(key)
                if cycle is not None and not in_progress.intersection(cycle):
                    # Enter a cycle only at its canonical first key.
                    pending = [k for k in cycle if k[1] not in memo[k[0]]]
                    if pending[0] != key:
                        stack.extend(reversed(pending))
                        continue
                in_progress.add(key)
            try:
                result = self._derive(key, in_progress)
            except _Missing as missing:
                stack.append(missing.key)
                continue
            memo[namespace][name] = result
            in_progress.discard(key)
            stack.pop()

    def _lookup(self, key: Key, in_progress: set[Key]) -> Resolution:
        namespace, name = key
        found = self._memo[namespace].get(name)
        if found is not None:
            return found
        if key in in_progress:
            return EMPTY
        facts = self.facts(namespace, name)
        if facts.decisive or name not in self._groups[namespace]:
            self._memo[namespace][name] = facts
            return facts
        reused = self._reused(key)
        if reused is not None:
            self._memo[namespace][name] = reused
            return reused
        raise _Missing(key)

    def _derive(self, key: Key, in_progress: set[Key]) -> Resolution:
        namespace, name = key
        facts = self.facts(namespace, name)
        if facts.decisive:  # a plain statement beats every preference
            return facts
        for rule in self._groups[namespace].get(name, ()):
            binding: Value | None = None
            holds = True
            for antecedent in rule.preference.antecedents:
                found = self._lookup((rule.namespace, antecedent.name), in_progress)
                if not found.literals:
                    found = self._lookup((1 - rule.namespace, antecedent.name), in_progress)
                holds, binding = antecedent_holds(antecedent, found.literals, binding)
                if not holds:
                    break
            if not holds:
                continue
            conclusion = instantiate(rule.preference.consequent, binding)
            if _excluded(conclusion, facts.literals):
                continue
            rest = tuple(x for x in facts.literals if x != conclusion)
            return Resolution((conclusion, *rest), True, rule, binding)
        return facts

    # -- beyond the first conclusion -----------------------------------------------

    def firing(self, key: Key) -> list[tuple[Rule, Literal, Value | None]]:
        """Every conditional default for ``key`` whose antecedents hold, in priority order."""
        result = []
        for rule in self.rules_for(key):
            binding = None
            holds = True
            for antecedent in rule.preference.antecedents:
                found = self.resolve(rule.namespace, antecedent.name)
                if not found.literals:
                    found = self.resolve(1 - rule.namespace, antecedent.name)
                holds, binding = antecedent_holds(antecedent, found.literals, binding)
                if not holds:
                    break
            if holds:
                result.append((rule, instantiate(rule.preference.consequent, binding), binding))
        return result


def antecedent_holds(
    antecedent: Literal, literals: tuple[Literal, ...], binding: Value | None
) -> tuple[bool, Value | None]:
    """Whether ``antecedent`` holds given what holds about its key; binds ``'-'``."""
    wanted = antecedent.value
    if wanted == ANY:
        if binding is not None:
            wanted = binding
        else:
            for literal in literals:
                if literal.negated == antecedent.negated and literal.value is not None:
                    return True, literal.value
            return False, binding
    if antecedent.negated:
        for literal in literals:
            if literal.negated and (literal.value is None or literal.value == wanted):
                return True, binding
        return False, binding
    for literal in literals:
        if literal.negated:
            continue
        if wanted is None:
            return True, binding
        value = literal.value
        if value == wanted or (isinstance(value, tuple) and wanted in value):
            return True, binding
    return False, binding


def instantiate(consequent: Literal, binding: Value | None) -> Literal:
    """The consequent with the captured value in place of ``'-'``."""
    if consequent.value == ANY and binding is not None:
        return consequent.with_value(binding)
    return consequent


def _excluded(conclusion: Literal, facts: tuple[Literal, ...]) -> bool:
    """Whether a weight-0 exclusion ``not(p=>v)`` rules the conclusion ``p=>v`` out."""
    if conclusion.negated or conclusion.value is None:
        return False
    return any(f.negated and f.value == conclusion.value for f in facts)
