"""KB atoms with accents (issue 22): read bare as SWI-Prolog does, written back as read,
and found by ``kb query`` whatever accents or case the person types."""

from __future__ import annotations

import json
import unicodedata
from pathlib import Path

import pytest

from homebot.cli import main
from homebot.errors import KnowledgeError
from homebot.knowledge import KnowledgeBase
from homebot.knowledge.syntax import read_kb_text, write_kb_text
from homebot.knowledge.terms import format_atom, parse_statement

ACENTOS = Path(__file__).resolve().parent / "data" / "acentos.kb"


def test_accented_atoms_are_read_bare() -> None:
    kb = KnowledgeBase.load(ACENTOS)
    assert kb.class_extension("residents") == ["josé", "søren", "patrícia"]
    assert kb.value("josé", "likes") == "crème_brûlée"
    assert kb.value("josé", "name") == "José"


def test_a_capital_first_is_a_variable_in_any_script() -> None:
    assert format_atom("josé") == "josé"
    assert format_atom("José") == "'José'"
    assert format_atom("Ørsted") == "'Ørsted'"
    with pytest.raises(KnowledgeError, match=r"the variable José .*quote it as 'José'"):
        parse_statement("name=>José")


def test_a_decomposed_accent_reads_as_the_composed_atom() -> None:
    statement = parse_statement(unicodedata.normalize("NFD", "likes=>crème_brûlée"))
    assert str(statement) == "likes=>crème_brûlée"


def test_written_text_keeps_the_letters_and_reads_back() -> None:
    taxonomy = read_kb_text(ACENTOS.read_text(encoding="utf-8"), str(ACENTOS))
    text = write_kb_text(taxonomy)
    assert "id=>josé" in text and "name=>'Søren'" in text
    assert write_kb_text(read_kb_text(text)) == text


@pytest.mark.parametrize("typed", ["josé", "jose", "JOSÉ"])
def test_kb_query_finds_an_individual_without_its_accents(
        typed: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["kb", "query", str(ACENTOS), "value", typed, "likes", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == "crème_brûlée"


def test_an_unknown_name_is_suggested_in_folded_form(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["kb", "query", str(ACENTOS), "value", "joss", "likes"]) == 2
    assert "did you mean 'josé'?" in capsys.readouterr().err
