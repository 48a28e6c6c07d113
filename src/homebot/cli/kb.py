"""``homebot kb check|query|explain``: check a KB file, ask it one of its services, explain."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from typing import Any

from homebot.errors import KnowledgeError
from homebot.knowledge import (
    Explanation,
    KnowledgeBase,
    Literal,
    Value,
)
from homebot.knowledge.coherence import warnings
from homebot.knowledge.knowledge_base import shipped_kb_path
from homebot.knowledge.syntax import kb_warnings
from homebot.knowledge.terms import format_literal, format_value
from homebot.text import find_name, problem_listing, terminal_safe

__all__ = ["SERVICES", "register", "to_json"]

#: Query services: name -> (argument names, what it answers).
SERVICES: dict[str, tuple[tuple[str, ...], str]] = {
    "class_extension": (("CLASS",), "individuals of a class and its subclasses"),
    "property_extension": (("PROPERTY",), "individuals with their value of a property"),
    "relation_extension": (("RELATION",), "individuals with the objects of a relation"),
    "explanation_extension": (("PROPERTY",), "individuals with an explanation of a property"),
    "classes_of_individual": (("INDIVIDUAL",), "an individual's class and its ancestors"),
    "properties_of_individual": (("INDIVIDUAL",), "every property that holds"),
    "relations_of_individual": (("INDIVIDUAL",), "every relation that holds"),
    "explanation_of_individual": (("INDIVIDUAL",), "explanations of what holds"),
    "value": (("ENTITY", "PROPERTY"), "yes, no, unknown or the value"),
    "values": (("ENTITY", "PROPERTY"), "all values in preference order"),
}


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("kb", help="check or query a non-monotonic knowledge base")
    kb_parsers = parser.add_subparsers(dest="kb_command", metavar="COMMAND")
    check = kb_parsers.add_parser("check", help="read a KB file and report problems")
    check.add_argument("file", help="KB file (.kb, .yaml, .db) or a shipped KB name")
    check.set_defaults(handler=_check)
    services = ", ".join(f"{name} {' '.join(a)}" for name, (a, _) in SERVICES.items())
    query = kb_parsers.add_parser(
        "query", help="ask a KB service", description=f"Services: {services}."
    )
    query.add_argument("file", help="KB file (.kb, .yaml, .db) or a shipped KB name")
    query.add_argument("service", help="one of: " + ", ".join(SERVICES))
    query.add_argument("arguments", nargs="*", metavar="ARG", help="the service's arguments")
    query.add_argument("--json", action="store_true", help="print the answer as JSON")
    query.set_defaults(handler=_query)
    explain = kb_parsers.add_parser("explain", help="explain what holds for an individual")
    explain.add_argument("file", help="KB file (.kb, .yaml, .db) or a shipped KB name")
    explain.add_argument("individual", help="the individual (or class) to explain")
    explain.set_defaults(handler=_explain)
    parser.set_defaults(handler=_no_command)


def _no_command(args: argparse.Namespace) -> int:
    raise KnowledgeError(
        "name a kb command: check FILE, query FILE SERVICE ARG..., explain FILE IND"
    )


def _check(args: argparse.Namespace) -> int:
    kb = KnowledgeBase.load(args.file)
    taxonomy = kb.taxonomy
    literals, preferences = taxonomy.statement_count()
    found = warnings(taxonomy)
    _print(
        f"{args.file}: ok — {len(taxonomy.classes)} classes, {len(taxonomy.individuals)} "
        f"individuals, {literals} literals, {preferences} conditional defaults, "
        f"{len(found)} warnings"
    )
    path = shipped_kb_path(args.file)
    if found and path.suffix.lower() not in (".yaml", ".yml", ".db", ".sqlite", ".sqlite3"):
        messages = kb_warnings(path)
    else:
        messages = [problem.message for problem in found]
    if messages:
        _print(problem_listing([f"warning: {message}" for message in messages]), lines=True)
    return 0


def _query(args: argparse.Namespace) -> int:
    service = args.service.replace("-", "_")
    if service not in SERVICES:
        raise KnowledgeError(
            f"unknown service '{args.service}'; expected one of: {', '.join(SERVICES)}"
        )
    expected = SERVICES[service][0]
    if len(args.arguments) != len(expected):
        raise KnowledgeError(
            f"{service} takes {' '.join(expected)}, got {len(args.arguments)} argument(s)"
        )
    kb = KnowledgeBase.load(args.file)
    method: Callable[..., Any] = getattr(kb, service)
    answer = method(*(_as_in_kb(kb, argument) for argument in args.arguments))
    if args.json:
        print(json.dumps(to_json(answer), ensure_ascii=False))
    else:
        _print(_to_text(answer))
    return 0


def _as_in_kb(kb: KnowledgeBase, name: str) -> str:
    """A class or individual as the KB spells it: "jose" finds josé (``homebot.text.fold``)."""
    taxonomy = kb.taxonomy
    if name in taxonomy.classes or name in taxonomy.individuals:
        return name
    return find_name(name, [*taxonomy.classes, *taxonomy.individuals]) or name


def _explain(args: argparse.Namespace) -> int:
    kb = KnowledgeBase.load(args.file)
    args.individual = _as_in_kb(kb, args.individual)
    explanations = kb.explanations(args.individual)
    if not explanations:
        _print(f"{args.individual}: nothing to explain")
    for explanation in explanations:
        because = (
            "by default"
            if not explanation.antecedents
            else f"because {explanation.antecedent_text}"
        )
        _print(
            f"{args.individual}: {format_literal(explanation.consequent)} {because} "
            f"(weight {explanation.weight}, from {explanation.source})"
        )
    return 0


def _print(text: str, *, lines: bool = False) -> None:
    """Print a line (or ``lines``) that quotes the KB's names, escaped for the terminal."""
    print(terminal_safe(text, lines=lines))


def to_json(answer: Any) -> Any:
    """JSON data for an answer: ``p=>v`` as ``{"p": "v"}``, ``not(x)`` as ``{"not": x}``,
    explanations and pairs as two-element lists."""
    if isinstance(answer, Literal):
        inner: Any = answer.name if answer.value is None else {answer.name: to_json(answer.value)}
        return {"not": inner} if answer.negated else inner
    if isinstance(answer, Explanation):
        antecedents = [to_json(a) for a in answer.antecedents]
        antecedent: Any = "-" if not antecedents else antecedents[0]
        if len(antecedents) > 1:
            antecedent = antecedents
        return [to_json(answer.consequent), antecedent]
    if isinstance(answer, list | tuple):
        return [to_json(item) for item in answer]
    return answer


def _to_text(answer: Any) -> str:
    if isinstance(answer, Literal):
        return format_literal(answer)
    if isinstance(answer, Explanation):
        return str(answer)
    if isinstance(answer, tuple) and len(answer) == 2 and isinstance(answer[0], str):
        return f"{answer[0]}:{_to_text(answer[1])}"
    if isinstance(answer, list):
        return "[" + ", ".join(_to_text(item) for item in answer) + "]"
    return _value_text(answer)


def _value_text(value: Value) -> str:
    return format_value(value)

