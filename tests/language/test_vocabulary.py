"""Vocabulary from a world, normalisation and misspellings."""

from __future__ import annotations

import pytest

import homebot.language
from homebot.errors import LanguageError
from homebot.language import Entity, Vocabulary
from homebot.language.normalise import normalise
from homebot.language.vocabulary import progressive


def test_exports_are_exactly_all() -> None:
    public = {name for name in dir(homebot.language) if not name.startswith("_")}
    modules = {"accounting", "clauses", "context", "fetching", "generator", "lexicon",
               "normalise", "parser", "people", "questions", "readings", "reporting", "result",
               "tagging",
               "vocabulary"}
    assert public - modules == set(homebot.language.__all__)


def test_world_names_and_plurals_are_known(vocabulary: Vocabulary) -> None:
    assert vocabulary.index[("living", "room")].value == (Entity("room", "living room"),)
    assert vocabulary.index[("cleaning", "supplies")].value == (
        Entity("category", "cleaning supply"),)
    assert vocabulary.index[("apples",)].value == (Entity("object", "apple"),)
    assert vocabulary.kind_of("Maria") == "person"


def test_head_nouns_are_ambiguous(vocabulary: Vocabulary) -> None:
    tables = {entity.name for entity in vocabulary.index[("table",)].value}
    assert {"kitchen table", "coffee table", "side table"} <= tables


def test_from_names_rejects_a_name_without_letters() -> None:
    with pytest.raises(LanguageError):
        Vocabulary.from_names(rooms=["--"], placements={}, objects={}, categories={},
                              people=[])


def test_normalise_expands_contractions_and_keeps_quotes(vocabulary: Vocabulary) -> None:
    result = normalise("What's the time? Say \"Hello, World\"", vocabulary)
    assert result.tokens[:2] == ("what", "is")
    assert result.quotes == ("Hello, World",)


def test_misspellings_are_corrected_to_known_words(vocabulary: Vocabulary) -> None:
    result = normalise("Bring the oragne juice to Sofie", vocabulary)
    assert "orange" in result.tokens and "sophie" in result.tokens
    assert ("oragne", "orange") in result.corrections


def test_short_and_function_words_are_never_corrected(vocabulary: Vocabulary) -> None:
    assert normalise("then them there", vocabulary).tokens == ("then", "them", "there")


@pytest.mark.parametrize("verb, form", [("bring", "bringing"), ("take", "taking"),
                                        ("put", "putting"), ("open", "opening")])
def test_progressive(verb: str, form: str) -> None:
    assert progressive(verb) == form
