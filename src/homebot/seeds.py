"""Seeds: the one range every command accepts for ``--seed``, and its argument type."""

from __future__ import annotations

from homebot.errors import OptionError

__all__ = ["MAX_SEED", "seed"]

MAX_SEED = 2**32 - 1  #: numpy's generators take seeds up to this


def seed(text: str) -> int:
    """An argument type for ``--seed``: a whole number from 0 to 2**32 - 1.

    A negative seed is refused rather than folded onto a positive one (``random.Random(-1)``
    plays as ``Random(1)``, so ``--seed -1`` would silently repeat ``--seed 1``).

    Raises:
        OptionError: for anything else, naming the option and the range.
    """
    stripped = text.strip()
    if not stripped.isdigit() or int(stripped) > MAX_SEED:
        hint = " (negative seeds are not used: -1 would play as 1)" if \
            stripped.startswith("-") else ""
        raise OptionError(f"--seed {text!r}: give a whole number from 0 to {MAX_SEED}{hint}")
    return int(stripped)
