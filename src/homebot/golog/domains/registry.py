"""The shipped domains by name, for the command line."""

from __future__ import annotations

from collections.abc import Callable

from homebot.errors import GologError
from homebot.golog.domains.blocks import blocks_theory
from homebot.golog.domains.cups import cups_theory
from homebot.golog.domains.elevator import elevator_theory
from homebot.golog.domains.maze import maze_theory
from homebot.golog.domains.rips import rips_theory
from homebot.golog.theory import Theory

__all__ = ["domain_names", "domain_theory"]


def _factories() -> dict[str, Callable[[], Theory]]:
    return {"blocks": blocks_theory, "elevator": elevator_theory, "maze": maze_theory,
            "rips": rips_theory,
            "cups": lambda: cups_theory({"red": "p2", "green": "p3", "blue": "p1"})}


def domain_names() -> list[str]:
    """Names of the shipped domains."""
    return sorted(_factories())


def domain_theory(name: str) -> Theory:
    """A fresh theory of a shipped domain (Order Cups starts with the cups in a 3-cycle)."""
    factory = _factories().get(name)
    if factory is None:
        raise GologError(f"no Golog domain '{name}'; choose one of {', '.join(domain_names())}")
    return factory()
