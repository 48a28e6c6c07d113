"""Hypothesis strategies and paths shared by the knowledge-base tests."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import strategies as st

from homebot.knowledge import ClassNode, IndividualNode, Literal, Preference, Taxonomy

REPOSITORY = Path(__file__).resolve().parents[2]
SHARED = REPOSITORY / ".." / "shared"
KB_GENERATOR = SHARED / "tools" / "kb_generator.py"
DATA_KB = REPOSITORY / "src" / "homebot" / "data" / "kb"

needs_shared = pytest.mark.skipif(
    not KB_GENERATOR.is_file(), reason="../shared (the KB generator) is absent"
)

NAMES = ("a", "b", "c", "d")
VALUES = ("x", "y", 1)


@st.composite
def literals(draw: st.DrawFn, *, allow_any: bool = False) -> Literal:
    values = [None, *VALUES, *(["-"] if allow_any else [])]
    return Literal(draw(st.sampled_from(NAMES)), draw(st.sampled_from(values)), draw(st.booleans()))


@st.composite
def preferences(draw: st.DrawFn) -> Preference:
    antecedents = tuple(draw(st.lists(literals(allow_any=True), max_size=2)))
    consequent = draw(literals(allow_any=any(a.captures for a in antecedents)))
    return Preference(antecedents, consequent, draw(st.integers(1, 4)))


statements = st.one_of(literals(), preferences())


@st.composite
def taxonomies(draw: st.DrawFn) -> Taxonomy:
    """Small random KBs: few names, so conflicts, chains and cycles are common."""
    taxonomy = Taxonomy()
    taxonomy.classes["top"] = ClassNode("top", None)
    for index in range(draw(st.integers(0, 4))):
        mother = draw(st.sampled_from(list(taxonomy.classes)))
        taxonomy.classes[f"k{index}"] = ClassNode(
            f"k{index}",
            mother,
            draw(st.lists(statements, max_size=4)),
            draw(st.lists(statements, max_size=2)),
        )
    for index in range(draw(st.integers(0, 4))):
        home = draw(st.sampled_from(list(taxonomy.classes)))
        name = f"i{index}"
        taxonomy.individuals[name] = IndividualNode(
            name,
            home,
            draw(st.lists(statements, max_size=3)),
            draw(st.lists(statements, max_size=2)),
        )
        taxonomy.classes[home].individuals.append(name)
    return taxonomy
