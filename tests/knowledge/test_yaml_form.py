"""The YAML form: round trips with the paper's syntax, errors with line and column."""

from __future__ import annotations

import contextlib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from kb_strategies import DATA_KB, taxonomies

from homebot.errors import KnowledgeError
from homebot.knowledge import (
    KnowledgeBase,
    Taxonomy,
    read_kb,
    read_kb_yaml,
    read_kb_yaml_text,
    write_kb_yaml,
    write_kb_yaml_text,
)


@pytest.mark.parametrize("name", ["animals.kb", "butler.kb"])
def test_shipped_kbs_survive_the_yaml_form(name: str, tmp_path: Path) -> None:
    taxonomy = read_kb(DATA_KB / name)
    path = tmp_path / "kb.yaml"
    write_kb_yaml(taxonomy, path)
    assert read_kb_yaml(path) == taxonomy
    assert KnowledgeBase.load(path).taxonomy == taxonomy


def test_the_yaml_form_reads_as_documented() -> None:
    taxonomy = read_kb_yaml_text(
        """
classes:
  - name: top
  - name: birds
    mother: top
    properties:
      - fly
      - not(swim)
      - {statement: "work=>'-'=>>live=>'-'", weight: 3}
    individuals:
      - name: pete
        relations: [work=>mexico]
"""
    )
    kb = KnowledgeBase(taxonomy)
    assert kb.value("pete", "live") == "mexico"
    assert kb.value("pete", "swim") == "no"


@pytest.mark.parametrize(
    ("text", "where", "expected"),
    [
        ("classes: [", "line 1, column 11", "expected"),
        ("classes:\n  - name: top\n    colour: red\n", "line 3, column 5", "colour"),
        ("classes:\n  - name: top\n    properties: [a=>b=>c]\n", "line 3, column 18", "=>"),
        (
            "classes:\n  - name: top\n    properties:\n      - {statement: 'a=>>b', weight: x}\n",
            "line 4, column 38",
            "whole-number weight",
        ),
        (
            "classes:\n  - name: top\n  - name: a\n    mother: nowhere\n",
            "line 4, column 13",
            "mother",
        ),
        ("classes:\n  - name: a\n", "", "no class 'top'"),
        ("classes:\n  - name: top\n  - name: top\n", "line 3, column 11", "not used before"),
        ("classes:\n  - mother: top\n", "line 2, column 5", "class name"),
        ("- just a list", "line 1, column 1", "a mapping"),
        (  # past Python's 4300 digits for reading an int
            "classes:\n  - name: top\n    properties:\n      - {statement: 'a=>>b', weight: "
            + "9" * 5000 + "}\n",
            "line 4, column 38",
            "whole-number weight",
        ),
    ],
)
def test_yaml_errors_name_line_column_and_what_was_expected(
    text: str, where: str, expected: str
) -> None:
    with pytest.raises(KnowledgeError) as raised:
        read_kb_yaml_text(text, "kb.yaml")
    assert where in str(raised.value)
    assert expected in str(raised.value)


@settings(max_examples=200, suppress_health_check=[HealthCheck.too_slow])
@given(taxonomies())
def test_written_yaml_reads_back_unchanged(taxonomy: Taxonomy) -> None:
    assert read_kb_yaml_text(write_kb_yaml_text(taxonomy)) == taxonomy


@settings(max_examples=300)
@given(st.text(max_size=80))
def test_random_yaml_raises_only_knowledge_errors(text: str) -> None:
    with contextlib.suppress(KnowledgeError):
        read_kb_yaml_text(text)
