"""Abduction: conditional defaults used backwards explain what holds (``Consequent : Ante``)."""

from __future__ import annotations

from dataclasses import dataclass

from homebot.knowledge.closure import Closure, antecedent_holds, instantiate
from homebot.knowledge.model import ANY, Literal, Value
from homebot.knowledge.terms import format_literal

__all__ = ["Explanation", "explain", "matches_pattern"]


@dataclass(frozen=True, slots=True)
class Explanation:
    """Why something holds: the most preferred default whose consequent it is.

    ``antecedents`` is empty for a default that holds always (``'-'``); ``source`` is
    the class or individual that states the default.
    """

    consequent: Literal
    antecedents: tuple[Literal, ...]
    weight: int
    source: str

    @property
    def antecedent_text(self) -> str:
        """The antecedent in KB syntax: ``'-'``, a literal, or a list of literals."""
        if not self.antecedents:
            return "'-'"
        if len(self.antecedents) == 1:
            return format_literal(self.antecedents[0])
        return "[" + ",".join(format_literal(a) for a in self.antecedents) + "]"

    def __str__(self) -> str:
        return f"{format_literal(self.consequent)} : {self.antecedent_text}"


def explain(closure: Closure) -> list[Explanation]:
    """Explanations of everything that holds for an entity, first one per consequent.

    Following Appendix B.3: every conditional default, in priority order, whose
    consequent holds (observed or derived) yields ``Consequent : Antecedent`` with the
    captured value put into the antecedent; only the first explanation of a consequent
    is kept. A default whose instantiated antecedent is known to be false is skipped.
    """
    explained: set[Literal] = set()
    result: list[Explanation] = []
    for rule in closure.rules:
        consequent = rule.preference.consequent
        holding = closure.resolve(rule.namespace, consequent.name).literals
        for literal in holding:
            if literal in explained:
                continue
            matched, binding = _match(consequent, literal)
            if not matched:
                continue
            antecedents = tuple(instantiate(a, binding) for a in rule.preference.antecedents)
            if any(_known_false(closure, rule.namespace, a) for a in antecedents):
                continue
            explained.add(literal)
            result.append(Explanation(literal, antecedents, rule.preference.weight, rule.source))
    return result


def _match(pattern: Literal, literal: Literal) -> tuple[bool, Value | None]:
    if pattern.negated != literal.negated:
        return False, None
    if pattern.value == ANY:
        return (literal.value is not None), literal.value
    return pattern.value == literal.value, None


def _known_false(closure: Closure, namespace: int, antecedent: Literal) -> bool:
    if antecedent.value == ANY:
        return False
    found = closure.resolve(namespace, antecedent.name).literals
    if not found:
        found = closure.resolve(1 - namespace, antecedent.name).literals
    holds, _ = antecedent_holds(antecedent.negation(), found, None)
    return holds


def matches_pattern(pattern: Literal, literal: Literal) -> bool:
    """Whether a query pattern names a literal: a bare name matches every value of it."""
    if pattern.name != literal.name or pattern.negated != literal.negated:
        return False
    return pattern.value in (None, ANY) or pattern.value == literal.value
