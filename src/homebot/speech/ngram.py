"""A trigram language model of a world's commands, written as ARPA for pocketsphinx.

Counted from sentences that ``homebot.language.generator`` produces for the world;
smoothed by absolute discounting with Katz-style back-off (discount ``D`` from every
seen n-gram, the freed mass given to the lower order in proportion to its probability
of the words not seen in that context). Written by hand, as it is a few dozen lines and
the well-known toolkits (SRILM, KenLM's lmplz) are native programs, not PyPI packages.
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Iterable
from dataclasses import dataclass

__all__ = ["NGramModel", "train_trigram"]

Gram = tuple[str, ...]
_DISCOUNT = 0.5


@dataclass(frozen=True)
class NGramModel:
    """log10 probabilities and back-off weights of 1-, 2- and 3-grams."""

    probabilities: dict[Gram, float]
    backoffs: dict[Gram, float]

    def vocabulary(self) -> set[str]:
        return {gram[0] for gram in self.probabilities if len(gram) == 1} - {"<s>", "</s>"}

    def arpa(self) -> str:
        """The model in ARPA text format."""
        orders: dict[int, list[Gram]] = defaultdict(list)
        for gram in self.probabilities:
            orders[len(gram)].append(gram)
        lines = ["", "\\data\\"]
        lines += [f"ngram {n}={len(orders[n])}" for n in (1, 2, 3)]
        for n in (1, 2, 3):
            lines += ["", f"\\{n}-grams:"]
            for gram in sorted(orders[n]):
                entry = f"{self.probabilities[gram]:.6f}\t{' '.join(gram)}"
                if n < 3 and gram in self.backoffs:
                    entry += f"\t{self.backoffs[gram]:.6f}"
                lines.append(entry)
        lines += ["", "\\end\\", ""]
        return "\n".join(lines)


def train_trigram(sentences: Iterable[str]) -> NGramModel:
    """A trigram model of ``sentences`` (each already lower case, words split by spaces)."""
    counts: list[Counter[Gram]] = [Counter(), Counter(), Counter()]
    for sentence in sentences:
        words = ["<s>", *sentence.split(), "</s>"]
        for n in (1, 2, 3):
            for start in range(len(words) - n + 1):
                counts[n - 1][tuple(words[start:start + n])] += 1
    unigrams, bigrams, trigrams = counts
    total = sum(count for gram, count in unigrams.items() if gram != ("<s>",))
    prob: dict[Gram, float] = {}
    for gram, count in unigrams.items():
        prob[gram] = count / total
    prob[("<s>",)] = 0.0
    raw: dict[Gram, float] = dict(prob)
    backoff: dict[Gram, float] = {}

    def lower(gram: Gram) -> float:
        """The model's probability of gram[-1] after gram[1:-1] (already final)."""
        if gram in raw:
            return raw[gram]
        return backoff.get(gram[:-1], 1.0) * lower(gram[1:])

    for table in (bigrams, trigrams):
        history_totals: Counter[Gram] = Counter()
        followers: dict[Gram, list[Gram]] = defaultdict(list)
        for gram, count in table.items():
            history_totals[gram[:-1]] += count
            followers[gram[:-1]].append(gram)
        new: dict[Gram, float] = {}
        for history, grams in followers.items():
            context = history_totals[history]
            for gram in grams:
                new[gram] = (table[gram] - _DISCOUNT) / context
            freed = _DISCOUNT * len(grams) / context
            seen_lower = sum(lower(gram[1:]) for gram in grams)
            backoff[history] = freed / max(1e-12, 1.0 - seen_lower)
        raw.update(new)
    probabilities = {gram: (math.log10(value) if value > 0 else -99.0)
                     for gram, value in raw.items()}
    return NGramModel(probabilities, {gram: math.log10(value) for gram, value in
                                      backoff.items() if value > 0})
