"""From what a person typed to clean tokens: case, contractions, quotes, misspellings."""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass

from rapidfuzz import fuzz, process
from rapidfuzz.distance import JaroWinkler

from homebot.language import lexicon
from homebot.language.vocabulary import Vocabulary
from homebot.text import fold

__all__ = ["QUOTE_MARK", "Normalised", "correct_spelling", "normalise"]

_QUOTED = re.compile(r"\"([^\"]+)\"|“([^”]+)”|«([^»]+)»")
_CONTRACTIONS = tuple((re.compile(rf"\b{re.escape(short)}\b"), long)
                      for short, long in lexicon.CONTRACTIONS)
_POSSESSIVE = re.compile(r"(?<=[^\W\d_])'s\b")
_BREAKS = re.compile(r"[,;:.!?]+")
_OTHER = re.compile(r"[^\w,' ]+|_+")  # after folding: letters of any script stay
_WORDS = re.compile(r"[^\W\d_]+|[.!?]")
QUOTE_MARK = "xquote"


@dataclass(frozen=True, slots=True)
class Normalised:
    """The tokens of a command (lower case, "," for clause breaks) and its quoted words.

    A quoted passage appears among the tokens as ``xquoteN`` (N its index).
    """

    tokens: tuple[str, ...]
    quotes: tuple[str, ...]
    corrections: tuple[tuple[str, str], ...]


def normalise(text: str, vocabulary: Vocabulary) -> Normalised:
    """Fold (``homebot.text.fold``: case and accents), expand contractions, split off
    quoted words (kept as written), fix misspelt names."""
    quotes: list[str] = []

    def keep_quote(match: re.Match[str]) -> str:
        quotes.append(next(group for group in match.groups() if group is not None).strip())
        return f" {QUOTE_MARK}{len(quotes) - 1} "

    text = unicodedata.normalize("NFKC", text)  # full-width letters, ligatures, odd spaces
    text = _QUOTED.sub(keep_quote, text.replace("’", "'").replace("‘", "'"))
    capitalised = _capitalised_words(text)
    lowered = fold(text)
    for pattern, long in _CONTRACTIONS:
        lowered = pattern.sub(long, lowered)
    lowered = _POSSESSIVE.sub("", lowered)  # "Tom's question": Tom
    lowered = _BREAKS.sub(" , ", lowered)
    raw = _OTHER.sub(" ", lowered).replace("'", "").split()
    tokens: list[str] = []
    corrections: list[tuple[str, str]] = []
    for token in raw:
        fixed = correct_spelling(token, vocabulary, as_name=token in capitalised)
        if fixed != token:
            corrections.append((token, fixed))
        tokens.append(fixed)
    while tokens and tokens[-1] == ",":
        tokens.pop()
    return Normalised(tuple(tokens), tuple(quotes), tuple(corrections))


def _capitalised_words(text: str) -> set[str]:
    """Words written with a capital inside a sentence: probably names."""
    words = _WORDS.findall(text)
    found = set()
    for previous, word in zip([".", *words], words, strict=False):
        if word[0].isupper() and previous not in {".", "!", "?"} and not word.isupper():
            found.add(fold(word))
    return found


def correct_spelling(token: str, vocabulary: Vocabulary, *, as_name: bool = False) -> str:
    """The known word closest to an unknown ``token`` (rapidfuzz), else ``token``.

    Only words of four letters or more are corrected, and only to a word the
    vocabulary knows, so function words and short words never change. A word
    written with a capital (``as_name``) is first compared with people's names by
    Jaro-Winkler similarity, which forgives swapped and doubled letters ("Jhon").
    """
    if (len(token) < 4 or not token.isalpha() or token in vocabulary.words
            or token in lexicon.FUNCTION_WORDS or token in lexicon.IMPOSSIBLE_ACTIONS
            or token in lexicon.COMMON_WORDS):
        return token
    if as_name and vocabulary.name_choices:
        name = process.extractOne(token, vocabulary.name_choices,
                                  scorer=JaroWinkler.normalized_similarity, score_cutoff=0.85)
        if name:
            return str(name[0])
    cutoff = 80.0 if len(token) >= 5 else 90.0  # "late" is not a misspelt "plate"
    match = process.extractOne(token, vocabulary.spelling_choices, scorer=fuzz.ratio,
                               score_cutoff=cutoff)
    return str(match[0]) if match else token
