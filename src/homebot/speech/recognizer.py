"""Hearing commands: two pocketsphinx decoders per utterance, reconciled as CAESAR does.

CAESAR (seeds/caesar-domestic-service-robot.txt §2.4) segments closed utterances, decodes
each with a finite-state grammar and with a trigram model in parallel, and looks for the
grammar's output in the trigram decoder's N-best list; what the two do not agree on is
rejected, which filters out the false positives of a noisy hall. Here:

- the grammar is ``command_grammar(world)`` (JSGF), the trigram model is trained on
  commands ``homebot.language.generator`` writes for the same world;
- a grammar hypothesis counts only when the grammar can produce it whole (pocketsphinx
  returns a partial path when no final state was reached);
- accepted: the two best hypotheses agree (``agree``), or the grammar's hypothesis is in
  the trigram decoder's N-best list (``nbest``), or an N-best entry differs from it in at
  most a third of its words (word edit distance, at least one word: ``similar``); when the
  grammar reached no final state, an N-best entry the grammar can produce whole and as
  close to its partial path is taken (``nbest_in_grammar``), or else the trigram's best
  hypothesis if the grammar can produce it whole (``ngram_in_grammar``); anything else is
  rejected, with the reason (``no_speech``, ``grammar_failed``, ``disagree``).

The similarity once also refused any difference in a slot word (a room, an object, a
name). Measured over 60 spoken commands (``homebot bench speech``'s voices, two worlds),
that rule rejected 7 of the grammar's right answers for each wrong one it kept out: the
trigram decoder misses the world's names more often than the grammar does (it has seen
each name in a few hundred contexts only), so its N-best differing in a name is weak
evidence against the grammar. Noise, tones and off-topic talk are still rejected because
the grammar reaches no final state on them, or its path shares little with the N-best.

Cosero (seeds/cosero-mobile-manipulation.txt §7.2.1) lets the task's state decide what is
understood: ``hear(audio, state="yes_no")`` listens with the yes/no grammar and its
model, ``state="drink"`` with the world's drinks.
"""

from __future__ import annotations

import itertools
import os
import random
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from rapidfuzz.distance import Levenshtein

from homebot.errors import SpeechError
from homebot.speech.audio import SAMPLE_RATE, Audio, denoise
from homebot.speech.grammar import (
    Grammar,
    command_grammar,
    drink_grammar,
    words_of,
    yes_no_grammar,
)
from homebot.speech.ngram import train_trigram
from homebot.speech.pronounce import build_dictionary
from homebot.speech.segmentation import Segmenter

__all__ = ["DIALOGUE_STATES", "Hearing", "Recognizer", "state_for_question"]

DIALOGUE_STATES = ("command", "yes_no", "drink")
_NBEST = 20
_DITHER_SEED = 12_345
_PAD = SAMPLE_RATE // 2
# The grammar's hypothesis is accepted when an N-best entry is within this share of its
# words (word edit distance, at least one word): CAESAR's "similarities".
_SIMILARITY = 1 / 3
_DECODER_OPTIONS: dict[str, Any] = {}
# The rules whose words are the world's names. Each of their words gets espeak-ng's
# pronunciation as a variant beside CMUdict's (``espeak_variants="slots"``, the default;
# True: every word, False: none): CMUdict has one US reading of "corridor" (K AO R AH D ER,
# K AO R IH D ER), and "corri-door" (K AO R IH D AO R) was heard as "office" or
# "wardrobe". Measured on a development set (seed 3, 100 commands per world, the bench
# voices): clean apartment 95 -> 98, RoboCup 95 -> 94 (a trigram flip), white noise 10 dB
# apartment 72 -> 74; held out (seed 7, two other voices, 40 per world): apartment 38 -> 39,
# RoboCup 38 -> 38.
# All words (True) gave RoboCup 94. The voices are espeak-ng's, so this is also what they
# say; people's pronunciations will differ.
_NAMING_RULES = ("room", "placement", "object", "category", "plural", "name", "drink")
# Spectral subtraction before decoding (``homebot.speech.audio.denoise``). Subtracting
# four times the noise estimate down to a floor of 5 % heard 23 of 31 commands in white
# noise at 10 dB as spoken against 19 with twice down to 10 % (and 14 with none); clean
# speech, whose quiet frames are near silence, passes almost unchanged.
_DENOISE: dict[str, float] = {"over": 4.0, "quiet_share": 0.1, "floor": 0.05}


@dataclass(frozen=True)
class Hearing:
    """What the robot heard in one utterance. ``text`` is None when it was rejected;
    ``reason`` says why it was accepted or rejected."""

    text: str | None
    reason: str
    state: str = "command"
    grammar_hypothesis: str | None = None
    ngram_hypotheses: tuple[str, ...] = ()
    seconds: float = 0.0
    decode_seconds: float = field(default=0.0, compare=False)

    def __bool__(self) -> bool:
        return self.text is not None

    def to_dict(self) -> dict[str, Any]:
        return {"text": self.text, "accepted": self.text is not None, "reason": self.reason,
                "state": self.state, "grammar": self.grammar_hypothesis,
                "ngram_nbest": list(self.ngram_hypotheses[:5]),
                "seconds": round(self.seconds, 3)}


def state_for_question(question: str) -> str:
    """The dialogue state a question puts the listener in: ``drink`` for a question about
    a drink, ``yes_no`` for a yes/no question (it starts with an auxiliary verb),
    otherwise ``command``."""
    words = words_of(question).split()
    if "drink" in words or "drinks" in words:
        return "drink"
    auxiliaries = {"do", "does", "did", "is", "are", "was", "should", "shall", "can",
                   "could", "may", "will", "would", "have", "has", "am"}
    return "yes_no" if words and words[0] in auxiliaries else "command"


def _rms(audio: Audio) -> float:
    return float(np.sqrt(np.mean(audio.astype(np.float64) ** 2))) if audio.size else 0.0


def _quietest(audio: Audio, length: int) -> Audio:
    """The ``length`` samples of ``audio`` with the least energy (10 ms steps)."""
    if audio.size <= length:
        return audio.copy()
    energy = np.concatenate([[0.0], np.cumsum(audio.astype(np.float64) ** 2)])
    starts = np.arange(0, audio.size - length + 1, SAMPLE_RATE // 100)
    start = int(starts[np.argmin(energy[starts + length] - energy[starts])])
    return audio[start:start + length].copy()


def _model_path() -> str:
    import pocketsphinx

    return os.path.join(pocketsphinx.get_model_path(), "en-us", "en-us")


class Recognizer:
    """pocketsphinx with a grammar and a trigram model for each dialogue state.

    Build it with ``Recognizer.for_world(world)``; ``hear(audio, state)`` segments the
    audio with the VAD and decodes the speech in it.
    """

    def __init__(self, grammars: Mapping[str, Grammar],
                 training: Mapping[str, list[str]], *,
                 segmenter: Segmenter | None = None, nbest: int = _NBEST,
                 similarity: float = _SIMILARITY, denoise: Mapping[str, float] | None = None,
                 decoder_options: Mapping[str, Any] | None = None,
                 espeak_variants: bool | str = "slots") -> None:
        try:
            import pocketsphinx
        except ImportError:
            raise SpeechError("speech recognition needs the speech extra: "
                              "pip install 'homebot[speech]'") from None
        self.grammars = dict(grammars)
        self.segmenter = segmenter or Segmenter()
        self.nbest = nbest
        self.similarity = similarity
        self.denoise = dict(_DENOISE if denoise is None else denoise)
        models = {state: train_trigram(training[state]) for state in self.grammars}
        words: set[str] = set()
        for state, grammar in self.grammars.items():
            words |= grammar.words() | models[state].vocabulary()
        variants: bool | set[str] = espeak_variants is True
        if espeak_variants == "slots":
            variants = {word for grammar in self.grammars.values()
                        for rule in _NAMING_RULES if rule in grammar.rules
                        for word in Grammar("", rule, grammar.rules, (rule,)).slot_words()}
        dictionary = build_dictionary(words, espeak_variants=variants)
        with tempfile.TemporaryDirectory(prefix="homebot-speech-") as folder:
            dict_path = os.path.join(folder, "words.dict")
            with open(dict_path, "w", encoding="utf-8") as handle:
                for word, pronunciations in dictionary.items():
                    for index, phones in enumerate(pronunciations):
                        suffix = f"({index + 1})" if index else ""
                        handle.write(f"{word}{suffix} {phones}\n")
            options = {**_DECODER_OPTIONS, **(decoder_options or {})}
            self._decoder = pocketsphinx.Decoder(hmm=_model_path(), dict=dict_path, lm=None,
                                                 loglevel="FATAL", **options)
            for state, grammar in self.grammars.items():
                self._decoder.add_jsgf_string(f"{state}_grammar", grammar.jsgf())
                arpa = os.path.join(folder, f"{state}.arpa")
                with open(arpa, "w", encoding="utf-8") as handle:
                    handle.write(models[state].arpa())
                self._decoder.add_lm_file(f"{state}_ngram", arpa)

    @classmethod
    def for_world(cls, world: Any, *, sentences: int = 5000, seed: int = 0,
                  segmenter: Segmenter | None = None, **options: Any) -> Recognizer:
        """Grammars and models for ``world``: its commands (the trigram model counts
        ``sentences`` generated commands, by ``seed``), yes/no, and its drinks."""
        from homebot.language.generator import generate_commands

        grammars = {"command": command_grammar(world), "yes_no": yes_no_grammar()}
        drinks = drink_grammar(world)
        if "<VOID>" not in drinks.rules["drink"]:
            grammars["drink"] = drinks
        rng = random.Random(seed)
        training = {"command": [words_of(text) for text, _ in
                                generate_commands(world, sentences, seed)]}
        for state, grammar in grammars.items():
            if state != "command":
                training[state] = grammar.sample(rng, 500)
        return cls(grammars, training, segmenter=segmenter, **options)

    # ------------------------------------------------------------------ decoding

    def _decode(self, audio: Audio, search: str) -> list[str]:
        """Hypotheses of one search, best first (one for a grammar, the N-best list for a
        trigram model)."""
        self._decoder.activate_search(search)
        self._decoder.start_utt()
        self._decoder.process_raw(audio.astype("<i2").tobytes(), full_utt=True)
        self._decoder.end_utt()
        best = self._decoder.hyp()
        if best is None:
            return []
        if search.endswith("_grammar"):
            return [best.hypstr]
        hypotheses = [best.hypstr]
        for entry in itertools.islice(self._decoder.nbest(), self.nbest * 3):
            if entry is None:
                continue
            text = " ".join(entry.hypstr.split())
            if text not in hypotheses:
                hypotheses.append(text)
            if len(hypotheses) >= self.nbest:
                break
        return [text for text in hypotheses if text]

    def decode(self, audio: Audio, state: str = "command") -> Hearing:
        """Decode ``audio`` as one utterance with both decoders and reconcile them."""
        if state not in self.grammars:
            raise SpeechError(f"no grammar for the dialogue state '{state}'; states: "
                              f"{', '.join(self.grammars)}")
        import time

        started = time.process_time()
        heard = audio
        # A recording that starts with the first word gets quiet before and after it, as a
        # person leaves it: the decoders' cepstral mean starts from a prior and needs a
        # moment. The quiet is the recording's own quietest half second (its background).
        pad = _quietest(heard, _PAD)
        if _rms(heard[:SAMPLE_RATE // 10]) > 3.0 * _rms(_quietest(heard, SAMPLE_RATE // 10)):
            heard = np.concatenate([pad, heard, pad])
        if self.denoise:
            heard = denoise(heard, **self.denoise)
        # A little seeded dither, last: pocketsphinx's features take the log of frame
        # energy, which digital silence (all zeros) makes meaningless. Before denoising it
        # was taken out of the quiet again (the quiet is what denoising removes), and the
        # grammar decoder then lost the last word of 4 in 100 slow clean commands.
        dither = np.random.default_rng(_DITHER_SEED).integers(-2, 3, size=heard.size)
        heard = np.clip(heard.astype(np.int32) + dither, -32768, 32767).astype(np.int16)
        grammar = self.grammars[state]
        fsg = self._decode(heard, f"{state}_grammar")
        nbest = tuple(self._decode(heard, f"{state}_ngram"))
        seconds = audio.size / SAMPLE_RATE
        elapsed = time.process_time() - started
        hypothesis = fsg[0] if fsg and fsg[0] and grammar.accepts(fsg[0]) else None

        def result(text: str | None, reason: str) -> Hearing:
            return Hearing(text, reason, state, fsg[0] if fsg else None, nbest, seconds,
                           elapsed)

        if hypothesis is None:
            # No final state reached: the grammar's partial path may still be close to an
            # N-best entry that the grammar can produce whole.
            partial = fsg[0].split() if fsg and fsg[0] else []
            if partial:
                for entry in nbest:
                    if (self._similar(entry.split(), partial)
                            and grammar.accepts(entry)):
                        return result(entry, "nbest_in_grammar")
            # The grammar's search lost its way, but the trigram's best is a whole
            # sentence of the grammar: both models accept it.
            if nbest and grammar.accepts(nbest[0]):
                return result(nbest[0], "ngram_in_grammar")
            return result(None, "grammar_failed")
        if nbest and nbest[0] == hypothesis:
            return result(hypothesis, "agree")
        if hypothesis in nbest:
            return result(hypothesis, "nbest")
        if any(self._similar(hypothesis.split(), entry.split()) for entry in nbest):
            return result(hypothesis, "similar")
        return result(None, "disagree")

    def _similar(self, words: list[str], other: list[str]) -> bool:
        """``words`` and ``other`` differ in at most ``similarity`` of ``words`` (word edit
        distance, at least one word)."""
        allowed = max(1, int(self.similarity * len(words)))
        return bool(Levenshtein.distance(words, other) <= allowed)

    def hear(self, audio: Audio, state: str = "command") -> Hearing:
        """Find the speech in ``audio`` (VAD) and decode it as one utterance, from the
        first speech to the last; ``no_speech`` when the VAD finds none."""
        utterances = self.segmenter.utterances(audio)
        if not utterances:
            return Hearing(None, "no_speech", state, seconds=audio.size / SAMPLE_RATE)
        return self.decode(audio[utterances[0].start:utterances[-1].end], state)
