"""The dialogue states answers are heard in (``homebot.speech.answers``): which state a
question calls for, what each state's grammar takes, and a denied answer giving way."""

from __future__ import annotations

import pytest

from homebot.speech.answers import (
    OPEN,
    answer_state,
    household_grammar,
    open_grammar,
    question_grammar,
)
from homebot.world import World


def test_a_question_calls_for_the_state_its_answer_is_heard_in() -> None:
    assert answer_state("Sophie, what is your name?") == "name"
    assert answer_state("What is your question?") == "question"
    assert answer_state("Where are you from?") == OPEN
    assert answer_state("Would you like something to drink?") == "drink"
    assert answer_state("Is the door open?") == "yes_no"


def test_open_answers_take_everyday_words_numbers_and_the_homes_names(
        apartment: World) -> None:
    grammar = open_grammar(apartment)
    for said in ("noodles", "i am from lyon", "twenty five years old", "orange juice",
                 "i said porto", "a cola please"):
        assert grammar.accepts(said), said
    assert not grammar.accepts("the weather is nice today")


def test_a_persons_question_about_the_home_is_a_sentence_of_its_own(
        apartment: World) -> None:
    grammar = question_grammar(apartment)
    assert grammar.accepts("how many rooms are there")
    assert grammar.accepts("where is the cola")
    assert not grammar.accepts("how many rooms on man")


def test_the_household_grammar_names_only_the_homes_people(apartment: World) -> None:
    grammar = household_grammar(apartment)
    assert grammar.accepts("my name is sophie")
    assert not grammar.accepts("my name is olivia")


def test_a_denied_answer_is_never_heard_again(apartment: World) -> None:
    pytest.importorskip("pocketsphinx")
    pytest.importorskip("espeakng_loader")
    import numpy as np

    from homebot.speech.answers import AnswerRecognizer
    from homebot.speech.grammar import words_of
    from homebot.speech.voice import VOICES, espeak

    recogniser = AnswerRecognizer(apartment)
    quiet = np.random.default_rng(0).normal(0, 30, 16_000).astype(np.int16)
    audio = np.concatenate([quiet, espeak().synthesise("My name is Sophie.", VOICES[1]),
                            quiet])
    first = recogniser.hear(audio, "name")
    assert first.text is not None and "sophie" in words_of(first.text)
    again = recogniser.hear(audio, "name", denied=(first.text,))
    assert again.text is None or "sophie" not in words_of(again.text)
