"""Golem-III's non-monotonic knowledge base: classes, defaults, preferences and abduction.

Fidelity to the original (SitLog's KB service, ``change_KB_extensions.pl``; compared by
``homebot bench kb_original`` when SWI-Prolog and a SitLog checkout are present). As in
the original: of equal-weight defaults for one property at one class level the one listed
last wins; the first ``not(p=>v)`` of a property is kept beside a value it does not
contradict (``a2=>v1`` with an inherited ``not(a2=>v3)``); literals are listed where they
are stated, the individual's own first, and derived conclusions in the order their
defaults fire. On a generated 10 000-individual KB (2 000 queries) 1 684 answers are
identical to the original's, 316 hold the same literals in another order, none differ
(before: 833 identical, 807 reordered, 360 different).

Where homebot keeps its own answer, on purpose:

- Every explicit exclusion counts. ``[[not(a=>v0),0],[not(a=>v1),0]]`` on an individual
  whose class says ``a=>v1``: the original keeps only the first negation and so answers
  ``[not(a=>v0),a=>v1]``, contradicting the individual; homebot answers
  ``[not(a=>v0),not(a=>v1)]`` and ``a`` stays unknown. Exclusions at or above the level
  that decides are all listed; below it, only the first (as in the original).
- Explanations name only antecedents that hold: ``explanation_of_individual`` cites the
  default that concluded a property. The original may explain a conclusion with an
  antecedent that is false or unknown for that individual (as issue 13 reports; the
  harness compares ``properties_of_individual`` only, not explanations).
- Several values stated at one level for one property (``loc=>shelf_food`` and
  ``loc=>shelf_snacks``) are all kept (``values``); the original keeps the first.
- Order, the one remaining difference on generated KBs: a property stated at two class
  levels (``not(a2=>v3)`` in the class, ``a2=>v0`` in its mother) is listed once, at the
  more specific place; the original lists each literal at its own level.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.lazy import lazy_exports

if TYPE_CHECKING:
    from homebot.knowledge.abduction import Explanation
    from homebot.knowledge.knowledge_base import UNKNOWN, Answer, KnowledgeBase
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
    from homebot.knowledge.syntax import read_kb, read_kb_text, write_kb, write_kb_text
    from homebot.knowledge.terms import parse_statement
    from homebot.knowledge.updates import (
        AddClass,
        AddIndividual,
        AddStatement,
        ChangeValue,
        ChangeWeight,
        MoveClass,
        MoveIndividual,
        RemoveClass,
        RemoveIndividual,
        RemoveStatement,
        Rename,
        Update,
    )
    from homebot.knowledge.yaml_form import (
        read_kb_yaml,
        read_kb_yaml_text,
        write_kb_yaml,
        write_kb_yaml_text,
    )

__all__ = [
    "ANY",
    "TOP",
    "UNKNOWN",
    "AddClass",
    "AddIndividual",
    "AddStatement",
    "Answer",
    "ChangeValue",
    "ChangeWeight",
    "ClassNode",
    "Explanation",
    "IndividualNode",
    "Kind",
    "KnowledgeBase",
    "Literal",
    "MoveClass",
    "MoveIndividual",
    "Preference",
    "RemoveClass",
    "RemoveIndividual",
    "RemoveStatement",
    "Rename",
    "Statement",
    "Taxonomy",
    "Touched",
    "Update",
    "Value",
    "parse_statement",
    "read_kb",
    "read_kb_text",
    "read_kb_yaml",
    "read_kb_yaml_text",
    "write_kb",
    "write_kb_text",
    "write_kb_yaml",
    "write_kb_yaml_text",
]

__getattr__ = lazy_exports(globals())
