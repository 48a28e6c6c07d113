"""Hearing answers: what a person says back when the robot asks them something.

Cosero (seeds/cosero-mobile-manipulation.txt §7.2.1) lets the question decide what is
listened for. ``answer_state(question)`` names the state: ``yes_no`` for a question that
starts with an auxiliary verb, ``drink`` for a question about drinks, ``name`` for "what is
your name?", else ``open``. The first three are heard with a grammar and a trigram model
of the answers (``AnswerRecognizer``, the ``Recognizer`` of CAESAR's two decoders), so
what is off the point is rejected; ``open`` answers (a question about the home, where
someone is from) go to pocketsphinx's general US English model and dictionary, taken as
heard.
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np

from homebot.errors import SpeechError
from homebot.speech.audio import Audio
from homebot.speech.grammar import drink_grammar, name_grammar, words_of, yes_no_grammar
from homebot.speech.recognizer import Hearing, Recognizer, state_for_question
from homebot.speech.segmentation import Segmenter

__all__ = ["OPEN", "AnswerRecognizer", "answer_state"]

OPEN = "open"
_NAME_QUESTIONS = {"what is your name", "what's your name", "whats your name", "who are you",
                   "may i have your name", "can you tell me your name"}
_SAMPLES_PER_STATE = 500


def answer_state(question: str) -> str:
    """The dialogue state ``question`` puts its listener in (see the module docstring)."""
    words = words_of(question)
    if any(words.endswith(asked) for asked in _NAME_QUESTIONS):
        return "name"
    state = state_for_question(question)
    return OPEN if state == "command" else state


class AnswerRecognizer:
    """Hears answers in every state of ``answer_state`` for ``world``'s names and drinks."""

    def __init__(self, world: Any, *, seed: int = 0,
                 segmenter: Segmenter | None = None) -> None:
        grammars = {"yes_no": yes_no_grammar(), "name": name_grammar(world)}
        drinks = drink_grammar(world)
        if "<VOID>" not in drinks.rules["drink"]:
            grammars["drink"] = drinks
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
        return (*self._states.grammars, OPEN)

    def hear(self, audio: Audio, state: str) -> Hearing:
        """The answer in ``audio`` (found by the VAD), heard in ``state``; a state this
        world has no grammar for (no drinks) is heard open."""
        if state in self._states.grammars:
            return self._states.hear(audio, state)
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
