"""Hearing answers: what a person says back when the robot asks them something.

Cosero (seeds/cosero-mobile-manipulation.txt §7.2.1) lets the question decide what is
listened for. ``answer_state(question)`` names the state: ``yes_no`` for a question that
starts with an auxiliary verb, ``drink`` for a question about drinks, ``name`` for "what is
your name?", ``question`` for "what is your question?" (a question about the home), else
``open``. Each is heard with a grammar and a trigram model of the answers
(``AnswerRecognizer``, the ``Recognizer`` of CAESAR's two decoders), so what is off the
point is rejected. An ``open`` answer (where someone is from, what they like) is heard
with ``open_grammar``: everyday answers, numbers and the home's names; one it rejects
goes to pocketsphinx's general US English model and dictionary, taken as heard. A name
is heard first among the home's own people (``household_grammar``), then among common
names too: a visitor misheard as someone of the home says no when the robot checks.
"""

from __future__ import annotations

import random
from collections.abc import Iterable
from dataclasses import replace
from typing import Any

import numpy as np

from homebot.errors import SpeechError
from homebot.speech.audio import Audio
from homebot.speech.grammar import (
    Grammar,
    drink_grammar,
    name_grammar,
    stop_grammar,
    words_of,
    yes_no_grammar,
)
from homebot.speech.recognizer import Hearing, Recognizer, state_for_question
from homebot.speech.segmentation import Segmenter

__all__ = ["EVERYDAY_ANSWERS", "OPEN", "STOP", "AnswerRecognizer", "answer_state",
           "household_grammar", "open_grammar", "question_grammar"]

OPEN = "open"
STOP = "stop"  #: said to end following or guiding
QUESTION = "question"
_HOUSEHOLD = "household_name"
#: What people commonly answer about themselves, beside the home's own names: foods,
#: where they come from, their age. A robot for homes is given this vocabulary as CAESAR's
#: and Cosero's were given their tasks' words; words outside it go to the open model.
EVERYDAY_ANSWERS: tuple[str, ...] = (
    # foods
    "apples", "bananas", "beans", "bread", "burgers", "cake", "cheese", "chicken",
    "chocolate", "curry", "eggs", "fish", "fruit", "ice cream", "lasagna", "meat",
    "noodles", "omelette", "pancakes", "pasta", "pizza", "potatoes", "rice", "salad",
    "sandwiches", "sausages", "soup", "spaghetti", "steak", "sushi", "tacos",
    "vegetables",
    # places people come from
    "amsterdam", "athens", "barcelona", "berlin", "bonn", "boston", "brazil", "canada",
    "china", "dublin", "england", "france", "germany", "india", "italy", "japan", "lisbon",
    "london", "lyon", "madrid", "mexico", "milan", "munich", "new york", "paris", "porto",
    "portugal", "rome", "spain", "tokyo", "toronto", "vienna",
    # drinks
    "coffee", "tea", "water", "milk", "juice", "beer", "wine", "lemonade", "cola",
)
_UNITS = ("one", "two", "three", "four", "five", "six", "seven", "eight", "nine")
_TEENS = ("ten", "eleven", "twelve", "thirteen", "fourteen", "fifteen", "sixteen",
          "seventeen", "eighteen", "nineteen")
_TENS = ("twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety")
_NAME_QUESTIONS = {"what is your name", "what's your name", "whats your name", "who are you",
                   "may i have your name", "can you tell me your name"}
_SAMPLES_PER_STATE = 500


def answer_state(question: str) -> str:
    """The dialogue state ``question`` puts its listener in (see the module docstring)."""
    words = words_of(question)
    if any(words.endswith(asked) for asked in _NAME_QUESTIONS):
        return "name"
    if words.endswith("what is your question"):
        return QUESTION
    state = state_for_question(question)
    return OPEN if state == "command" else state


def household_grammar(world: Any) -> Grammar:
    """A name answer naming one of the home's own people (``name_grammar`` without the
    common names of visitors)."""
    names = name_grammar(world)
    return Grammar("household", "answer", {
        "answer": names.rules["answer"], "name": _alternatives(world.people)},
        slots=("name",))


def question_grammar(world: Any) -> Grammar:
    """What a person asks the robot about the home when asked for their question, as
    ``homebot.skills.interaction.answer_about_home`` answers it."""
    return Grammar("questions", "answer", {
        "answer": ("how many (rooms | people) are there | how many people live here "
                   "| where (is | are) the <object> | what time is it | what day is it "
                   "| what day is today"),
        "object": _alternatives([*world.objects,
                                 *(obj.category for obj in world.objects.values())]),
    }, slots=("object",))


def _alternatives(phrases: Iterable[str]) -> str:
    return " | ".join(sorted({words_of(phrase) for phrase in phrases} - {""}))


def _numbers() -> list[str]:
    return [*_UNITS, *_TEENS, *_TENS,
            *(f"{tens} {unit}" for tens in _TENS for unit in _UNITS)]


def open_grammar(world: Any) -> Grammar:
    """An answer about oneself ("where are you from?", "how old are you?"): one of
    ``EVERYDAY_ANSWERS``, a number, or a name of the home (its objects, their categories,
    its people), alone or after a short frame."""
    things = [*EVERYDAY_ANSWERS, *world.objects, *world.people,
              *(obj.category for obj in world.objects.values())]
    return Grammar("answers", "answer", {
        "answer": ("[i am from | i come from | i would like | i like | i want | i am "
                   "| my favourite is | i would say | i said] [a | an | some] (<object> | <age>) "
                   "[please]"),
        # "object": the recogniser gives these words espeak-ng's pronunciation too
        "object": _alternatives(things),
        "age": "<number> [years old]",
        "number": _alternatives(_numbers()),
    }, slots=("object", "number"))


def _slot_words(grammar: Grammar, text: str) -> frozenset[str]:
    return frozenset(words_of(text).split()) & grammar.slot_words()


class AnswerRecognizer:
    """Hears answers in every state of ``answer_state`` for ``world``'s names and drinks."""

    def __init__(self, world: Any, *, seed: int = 0,
                 segmenter: Segmenter | None = None) -> None:
        grammars = {"yes_no": yes_no_grammar(), "name": name_grammar(world),
                    _HOUSEHOLD: household_grammar(world),
                    QUESTION: question_grammar(world), OPEN: open_grammar(world)}
        drinks = drink_grammar(world)
        if "<VOID>" not in drinks.rules["drink"]:
            grammars["drink"] = drinks
        grammars[STOP] = stop_grammar()
        rng = random.Random(seed)
        training = {state: grammar.sample(rng, _SAMPLES_PER_STATE)
                    for state, grammar in grammars.items()}
        self.segmenter = segmenter or Segmenter()
        self._states = Recognizer(grammars, training, segmenter=self.segmenter)
        try:
            import pocketsphinx
        except ImportError:  # pragma: no cover - Recognizer raised first
            raise SpeechError("speech recognition needs the speech extra: "
                              "pip install 'homebot[speech]'") from None
        self._open = pocketsphinx.Decoder(loglevel="FATAL")

    @property
    def states(self) -> tuple[str, ...]:
        return tuple(state for state in self._states.grammars if state != _HOUSEHOLD)

    def hear(self, audio: Audio, state: str, denied: tuple[str, ...] = ()) -> Hearing:
        """The answer in ``audio`` (found by the VAD), heard in ``state``; a state this
        world has no grammar for (no drinks) is heard open. An open answer the open
        grammar rejects is heard by the general model, taken as heard. An answer that
        names what a ``denied`` answer named (the person said it was misheard) gives way
        to the trigram decoder's best other hypothesis the grammar can produce whole."""
        if state not in self.states:
            state = OPEN
        if state == "name":
            # the people of the home first: far likelier than any other name
            known = self._states.hear(audio, _HOUSEHOLD)
            if known.text is not None and denied:
                known = self._not_denied(known, _HOUSEHOLD, denied)
            if known.text is not None:
                return replace(known, state="name")
        heard = self._states.hear(audio, state)
        if heard.text is not None and denied:
            heard = self._not_denied(heard, state, denied)
        if heard.text is not None or state != OPEN or heard.reason in ("no_speech", "denied"):
            return heard
        utterances = self.segmenter.utterances(audio)
        seconds = audio.size / 16_000
        if not utterances:
            return Hearing(None, "no_speech", OPEN, seconds=seconds)
        speech = audio[utterances[0].start:utterances[-1].end]
        self._open.start_utt()
        self._open.process_raw(np.asarray(speech, dtype="<i2").tobytes(), full_utt=True)
        self._open.end_utt()
        best = self._open.hyp()
        text = " ".join(best.hypstr.split()) if best is not None else ""
        return Hearing(text or None, "open" if text else "no_words", OPEN, seconds=seconds)

    def _not_denied(self, heard: Hearing, state: str, denied: tuple[str, ...]) -> Hearing:
        grammar = self._states.grammars[state]
        refused = {_slot_words(grammar, text) for text in denied}
        if _slot_words(grammar, heard.text or "") not in refused:
            return heard
        for entry in heard.ngram_hypotheses:
            named = _slot_words(grammar, entry)
            if named and named not in refused and grammar.accepts(entry):
                return replace(heard, text=entry, reason="nbest_not_denied")
        return replace(heard, text=None, reason="denied")
