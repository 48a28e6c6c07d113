"""The folded form names are compared in: accents, case and Unicode forms set aside; names
and problem lists shown safely."""

from __future__ import annotations

import unicodedata

from hypothesis import given
from hypothesis import strategies as st

from homebot.text import (
    MOST_LISTED,
    closest_names,
    find_name,
    fold,
    folded_index,
    problem_listing,
    terminal_safe,
)


def test_accented_and_plain_spellings_fold_alike() -> None:
    assert fold("Patrícia") == fold("patricia") == fold("PATRÍCIA") == "patricia"
    assert fold("Antônia") == "antonia"
    assert fold("José") == "jose"
    assert fold("Zoë") == "zoe"
    assert fold("crème brûlée") == "creme brulee"
    assert fold("Straße") == "strasse"


def test_letters_without_a_decomposition_fold_to_what_keyboards_write() -> None:
    assert fold("Søren") == fold("SØREN") == "soren"
    assert fold("smørrebrød") == "smorrebrod"
    assert fold("Æbleskiver") == "aebleskiver"
    assert fold("Łukasz") == "lukasz"


def test_composed_and_decomposed_and_compatibility_forms_fold_alike() -> None:
    composed = unicodedata.normalize("NFC", "Patrícia")
    decomposed = unicodedata.normalize("NFD", "Patrícia")
    assert composed != decomposed
    assert fold(composed) == fold(decomposed) == "patricia"
    assert fold("ｃｏｌａ") == "cola"  # full-width letters
    assert fold("ﬁsh") == "fish"  # a ligature


def test_other_scripts_keep_their_letters() -> None:
    assert fold("Анна") == "анна"
    assert fold("Ἀθηνᾶ") == "αθηνα"


@given(st.text())
def test_folding_is_idempotent(text: str) -> None:
    assert fold(fold(text)) == fold(text)


@given(st.text())
def test_folding_ignores_case_and_accents_already_removed(text: str) -> None:
    assert fold(text.upper()) == fold(fold(text).upper())


def test_names_are_found_as_written() -> None:
    people = ["José", "Antônia", "Søren", "Patrícia"]
    assert find_name("patricia", people) == "Patrícia"
    assert find_name("SOREN", people) == "Søren"
    assert find_name("Paula", people) is None
    assert folded_index(people)["antonia"] == "Antônia"
    assert closest_names("patrica", people) == ["Patrícia"]
    assert closest_names("Jóse", people) == ["José"]
    assert closest_names("xyz", people) == []


def test_the_text_module_imports_nothing_of_homebot() -> None:
    """Every layer folds names, the world included, so ``homebot.text`` sits below them all."""
    import ast
    from pathlib import Path

    import homebot.text

    tree = ast.parse(Path(homebot.text.__file__).read_text(encoding="utf-8"))
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import)
                for alias in node.names}
    imported |= {node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    assert not {name for name in imported if name.split(".")[0] == "homebot"}


def test_terminal_safe_escapes_what_a_terminal_would_act_on() -> None:
    assert terminal_safe("evil\x1b[2J\x07\x9b\u202ered\x7f") == (
        "evil\\x1b[2J\\x07\\x9b\\u202ered\\x7f")
    assert terminal_safe("a\nb\tc") == "a\\x0ab\tc"  # one line stays one line
    assert terminal_safe("a\nb", lines=True) == "a\nb"
    assert terminal_safe("Søren [bold] 'x'") == "Søren [bold] 'x'"  # text is left alone


def test_problem_listing_shows_the_first_and_counts_the_rest() -> None:
    problems = [f"problem {n}" for n in range(MOST_LISTED + 1_234)]
    lines = problem_listing(problems).splitlines()
    assert lines[:MOST_LISTED] == problems[:MOST_LISTED]
    assert lines[MOST_LISTED:] == ["... and 1,234 more"]
    assert problem_listing(problems[:MOST_LISTED]) == "\n".join(problems[:MOST_LISTED])
