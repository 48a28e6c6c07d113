"""Pronunciations for the recogniser: CMUdict, and espeak-ng's IPA for words it lacks.

World names like "cheezit" or "trashbin" are not in the CMU dictionary that pocketsphinx
ships. espeak-ng knows how to say any word; its IPA is mapped to the ARPAbet phones of
the en-US acoustic model (longest symbol first).
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping

from homebot.errors import SpeechError

__all__ = ["build_dictionary", "cmudict_path", "ipa_to_arpabet"]

_IPA: dict[str, str] = {
    "tʃ": "CH", "dʒ": "JH", "eɪ": "EY", "aɪ": "AY", "ɔɪ": "OY", "aʊ": "AW", "oʊ": "OW",
    "əʊ": "OW", "iː": "IY", "i": "IY", "ɪ": "IH", "ᵻ": "IH", "uː": "UW", "u": "UW",
    "ʊ": "UH", "ɛ": "EH", "e": "EH", "æ": "AE", "a": "AE", "ɑː": "AA", "ɑ": "AA",
    "ɒ": "AA", "ɔː": "AO", "ɔ": "AO", "ʌ": "AH", "ə": "AH", "ɐ": "AH", "ɚ": "ER",
    "ɜː": "ER", "ɜ": "ER", "ɝ": "ER", "p": "P", "b": "B", "t": "T", "d": "D", "k": "K",
    "ɡ": "G", "g": "G", "f": "F", "v": "V", "θ": "TH", "ð": "DH", "s": "S", "z": "Z",
    "ʃ": "SH", "ʒ": "ZH", "h": "HH", "m": "M", "n": "N", "ŋ": "NG", "l": "L", "ɹ": "R",
    "r": "R", "w": "W", "j": "Y", "ɾ": "T", "x": "K", "ɬ": "L",
}
_LONGEST = max(len(symbol) for symbol in _IPA)


def ipa_to_arpabet(ipa: str) -> list[str]:
    """ARPAbet phones for an IPA string; stress, length and unknown marks are skipped."""
    phones: list[str] = []
    position = 0
    while position < len(ipa):
        for size in range(_LONGEST, 0, -1):
            symbol = ipa[position:position + size]
            if symbol in _IPA:
                phones.append(_IPA[symbol])
                position += size
                break
        else:
            position += 1  # stress ˈˌ, length ː on its own, syllable marks, spaces
    return phones


def cmudict_path() -> str:
    """The CMU dictionary shipped with pocketsphinx's en-US model."""
    import pocketsphinx

    return os.path.join(pocketsphinx.get_model_path(), "en-us", "cmudict-en-us.dict")


def _read_cmudict(words: set[str]) -> dict[str, list[str]]:
    found: dict[str, list[str]] = {}
    with open(cmudict_path(), encoding="utf-8") as handle:
        for line in handle:
            head, _, phones = line.partition(" ")
            word = head.split("(")[0]
            if word in words:
                found.setdefault(word, []).append(phones.strip())
    return {word: found[word] for word in sorted(found)}


def build_dictionary(words: Iterable[str], speak: object | None = None, *,
                     espeak_variants: bool | Iterable[str] = False
                     ) -> Mapping[str, list[str]]:
    """Every word with its pronunciations (several where CMUdict has variants).

    Words CMUdict lacks are pronounced by espeak-ng (``speak`` is a ``Voice``; the shared
    one when None); with ``espeak_variants`` every word also gets espeak-ng's pronunciation
    as a variant (given words, only those). Raises ``SpeechError`` for a word nobody can pronounce.
    """
    wanted = {word for word in words if word}
    known = _read_cmudict(wanted)
    missing = sorted(wanted - set(known))
    if espeak_variants is True:
        missing = sorted(wanted)
    elif espeak_variants:
        missing = sorted(set(missing) | (wanted & set(espeak_variants)))
    if missing:
        from homebot.speech.voice import Voice, espeak

        voice = speak if isinstance(speak, Voice) else espeak()
        for word in missing:
            phones = ipa_to_arpabet(voice.phonemes(word))
            if not phones:
                raise SpeechError(f"the word '{word}' has no pronunciation; rename it in "
                                  "the world file with letters a-z")
            variant = " ".join(phones)
            if word not in known:
                known[word] = [variant]
            elif variant not in known[word]:
                known[word].append(variant)
    return known
