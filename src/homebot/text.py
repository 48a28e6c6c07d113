"""Names compared as people mean them: one folded form, whatever the accents or the case;
and shown safely.

"Patrícia", "patricia" and "PATRÍCIA" are one name; so are "Søren" and "Soren". Every
comparison of a name with what a person typed, said or wrote in a file goes through
``fold`` (or ``find_name`` / ``closest_names``, built on it), on both sides; what is
shown keeps the spelling of the file that defined the name, through ``terminal_safe``,
so a name cannot carry escape sequences to the terminal; a long list of problems is
shown through ``problem_listing``, the first twenty and a count of the rest. This module imports
nothing of homebot, so every layer (the world included) may use it.
"""

from __future__ import annotations

import difflib
import re
import unicodedata
from collections.abc import Iterable, Sequence

__all__ = ["MOST_LISTED", "closest_names", "find_name", "fold", "folded_index",
           "problem_listing", "terminal_safe"]

#: The most problems one message lists; a file with 200,000 of them once printed 21.5 MB.
MOST_LISTED = 20

# What a terminal acts on rather than shows: C0 and C1 controls (escape sequences, bell,
# carriage return, backspace), DEL, and the bidirectional overrides that reorder a line.
# A tab is only white space; newlines are kept where a text is meant to be lines.
_CONTROLS = r"\x00-\x08\x0b-\x1f\x7f-\x9f\u200e\u200f\u202a-\u202e\u2066-\u2069"
_UNSAFE = re.compile(f"[{_CONTROLS}\n]")
_UNSAFE_BUT_LINES = re.compile(f"[{_CONTROLS}]")

# Letters Unicode does not decompose into a base letter and a mark, written the way a
# keyboard or a speech recogniser without them writes them ("Søren" -> "soren").
_UNDECOMPOSED = str.maketrans({
    "ø": "o", "æ": "ae", "œ": "oe", "ł": "l", "đ": "d", "ð": "d", "þ": "th", "ı": "i",
    "ħ": "h", "ŧ": "t", "ŀ": "l", "ĸ": "k", "ŋ": "n",
})


def fold(text: str) -> str:
    """The form names are compared in: case-folded, Unicode NFKD, combining marks removed.

    A few letters that have no decomposition (ø, æ, œ, ł, đ, ð, þ, ı) become the plain
    letters people type for them. ``fold(fold(t)) == fold(t)`` for every text.
    """
    if text.isascii():
        return text.lower()
    # Twice: a compatibility character may decompose to a capital ("ℌ" -> "H").
    return _unmarked(_unmarked(text)).translate(_UNDECOMPOSED)


def _unmarked(text: str) -> str:
    decomposed = unicodedata.normalize("NFKD", text.casefold())
    return "".join(char for char in decomposed if not unicodedata.combining(char))


def folded_index(names: Iterable[str]) -> dict[str, str]:
    """Each name's folded form -> the name as written (the first one, on a clash)."""
    index: dict[str, str] = {}
    for name in names:
        index.setdefault(fold(name), name)
    return index


def find_name(text: str, names: Iterable[str]) -> str | None:
    """The name among ``names`` that ``text`` spells, ignoring accents and case, as written."""
    wanted = fold(text)
    return next((name for name in names if fold(name) == wanted), None)


def closest_names(text: str, names: Iterable[str], count: int = 1,
                  cutoff: float = 0.6) -> list[str]:
    """The names most like ``text`` compared in folded form (difflib), as written."""
    index = folded_index(names)
    return [index[match] for match in
            difflib.get_close_matches(fold(text), list(index), n=count, cutoff=cutoff)]


def terminal_safe(text: str, *, lines: bool = False) -> str:
    """``text`` with every control character written out as an escape (``\\x1b``,
    ``\\u202e``), for printing what a file or a person supplied to a terminal.

    With ``lines`` newlines stay (a listing of many lines); otherwise they are escaped too,
    so one message stays one line.
    """
    pattern = _UNSAFE_BUT_LINES if lines else _UNSAFE
    return pattern.sub(_escaped, text)


def _escaped(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def problem_listing(problems: Sequence[str], most: int = MOST_LISTED) -> str:
    """``problems`` one a line: the first ``most``, then ``... and N more`` for the rest."""
    shown = list(problems[:most])
    if len(problems) > most:
        shown.append(f"... and {len(problems) - most:,} more")
    return "\n".join(shown)
