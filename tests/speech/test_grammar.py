"""Grammars: every generated command is in the world's grammar; off-topic talk is not."""

from __future__ import annotations

import random

import pytest

from homebot.language.generator import generate_commands
from homebot.speech.grammar import command_grammar, drink_grammar, words_of, yes_no_grammar
from homebot.speech.ngram import train_trigram
from homebot.speech.pronounce import ipa_to_arpabet
from homebot.world import World


def test_every_generated_command_is_in_the_grammar(apartment: World,
                                                   supermarket: World) -> None:
    for world in (apartment, supermarket):
        grammar = command_grammar(world)
        for text, _ in generate_commands(world, 400, seed=7):
            assert grammar.accepts(text), text


def test_off_topic_and_broken_commands_are_not(apartment: World) -> None:
    grammar = command_grammar(apartment)
    for text in ("the weather is nice today", "bring me the moon",
                 "bring me a cola from the", "go to the kitchen then",
                 "bring me a cola from the garage"):
        assert not grammar.accepts(text), text


def test_dialogue_state_grammars(apartment: World) -> None:
    yes_no, drinks = yes_no_grammar(), drink_grammar(apartment)
    assert yes_no.accepts("Yes, please.") and yes_no.accepts("no thanks")
    assert not yes_no.accepts("bring me a cola")
    assert drinks.accepts("I would like an orange juice please")
    assert drinks.accepts("cola")
    assert not drinks.accepts("I would like a banana")  # food, not a drink


def test_sampled_sentences_stay_in_their_grammar(apartment: World) -> None:
    rng = random.Random(2)
    for grammar in (yes_no_grammar(), drink_grammar(apartment), command_grammar(apartment)):
        sentences = grammar.sample(rng, 200)
        assert all(grammar.accepts(sentence) for sentence in sentences)
        assert len(set(sentences)) > 5


def test_jsgf_names_each_rule_once_and_one_public(apartment: World) -> None:
    text = command_grammar(apartment).jsgf()
    assert text.startswith("#JSGF V1.0;")
    assert text.count("public <") == 1
    assert "<room> = bathroom | bedroom | corridor | entrance | kitchen | living room" in text


@pytest.mark.parametrize(("ipa", "arpabet"), [
    ("tʃˈiːzɪt", "CH IY Z IH T"), ("tɹˈæʃbɪn", "T R AE SH B IH N"),
    ("kˈoʊtɹæk", "K OW T R AE K"), ("pɹˈɪŋɡəlz", "P R IH NG G AH L Z"),
])
def test_ipa_maps_to_the_models_phones(ipa: str, arpabet: str) -> None:
    assert " ".join(ipa_to_arpabet(ipa)) == arpabet


def test_the_trigram_model_is_a_distribution(apartment: World) -> None:
    sentences = [words_of(text) for text, _ in generate_commands(apartment, 300, seed=1)]
    model = train_trigram(sentences)
    vocabulary = [*sorted(model.vocabulary()), "</s>"]

    def probability(history: tuple[str, ...], word: str) -> float:
        gram = (*history, word)
        if gram in model.probabilities:
            return float(10 ** model.probabilities[gram])
        return float(10 ** model.backoffs.get(history, 0.0)) * probability(history[1:], word)

    for history in [("<s>",), ("bring",), ("<s>", "bring"), ("the", "kitchen"),
                    ("from", "the"), ("zebra",)]:
        total = sum(probability(history, word) for word in vocabulary)
        assert total == pytest.approx(1.0, abs=1e-6), history
    arpa = model.arpa()
    assert "\\data\\" in arpa and "\\3-grams:" in arpa and arpa.rstrip().endswith("\\end\\")
