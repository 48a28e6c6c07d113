"""Qualitative fluents for Golog theories: ``dist(A, B)``, ``orient(A, B)`` and ``is(v, c)``.

CAESAR's programs test qualitative positions directly (Alg. 1, line 12:
``is(dist(x, y, x1, y1), close)``). ``add_qualitative(theory, frame)`` declares:

- ``dist(A, B)``: the fuzzy qualitative distance between two points (x, y), read in
  the frame ``frame(A, B)`` names (its scale): a ``Fuzzy`` value holding the
  membership of each of ``very_close`` … ``very_far``;
- ``orient(A, B)``: the fuzzy orientation of B seen from A against that frame's
  front side (intrinsic reference): memberships of the eight sectors;
- ``is(V, C)``: V holds category C at least as much as any other, and with at
  least 0.5 (on a boundary both neighbours hold);
- ``degree(V, C)``: the membership itself, a number from 0 to 1.

A and B are the values of fluents or functions (``pos(obj)``, ``robot``), so the
qualitative relations follow the situation as the robot's model progresses.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from homebot.errors import GologError
from homebot.golog.theory import State, Theory
from homebot.space.distance import DISTANCES, distance_memberships
from homebot.space.orientation import ORIENTATIONS, intrinsic_angle, orientation_memberships

__all__ = ["FrameOf", "Fuzzy", "add_qualitative"]

Point = tuple[float, float]
#: the frame two points are read in: (scale in metres, front heading in radians)
FrameOf = Callable[[Point, Point], tuple[float, float]]


@dataclass(frozen=True, slots=True)
class Fuzzy:
    """A qualitative value: the membership of each category."""

    categories: tuple[str, ...]
    degrees: tuple[float, ...]

    def degree(self, category: str) -> float:
        if category not in self.categories:
            raise GologError(f"'{category}' is not one of {', '.join(self.categories)}; "
                             "test a category of the value's own kind")
        return self.degrees[self.categories.index(category)]

    def holds(self, category: str) -> bool:
        degree = self.degree(category)
        return degree >= 0.5 and degree >= max(self.degrees) - 1e-12

    def __str__(self) -> str:
        best = max(range(len(self.degrees)), key=lambda index: self.degrees[index])
        return f"{self.categories[best]}({self.degrees[best]:.2f})"


def _point(value: Any, what: str) -> Point:
    if (isinstance(value, tuple) and len(value) == 2
            and all(isinstance(v, int | float) for v in value)):
        return (float(value[0]), float(value[1]))
    raise GologError(f"{what} needs two points (x, y), not {value!r}; give positions such "
                     "as pos(obj)")


def add_qualitative(theory: Theory, frame: FrameOf) -> None:
    """Declare ``dist``, ``orient``, ``is`` and ``degree`` in ``theory``."""

    def dist(state: State, first: Any, second: Any) -> Fuzzy:
        a, b = _point(first, "dist"), _point(second, "dist")
        scale, _ = frame(a, b)
        return Fuzzy(DISTANCES, distance_memberships(math.dist(a, b), scale))

    def orient(state: State, first: Any, second: Any) -> Fuzzy:
        a, b = _point(first, "orient"), _point(second, "orient")
        _, front = frame(a, b)
        return Fuzzy(ORIENTATIONS, orientation_memberships(intrinsic_angle(b, a, front)))

    def is_(state: State, value: Any, category: Any) -> bool:
        if not isinstance(value, Fuzzy):
            raise GologError(f"is(V, C) tests a qualitative value such as dist(A, B), "
                             f"not {value!r}")
        return value.holds(str(category))

    def degree(state: State, value: Any, category: Any) -> float:
        if not isinstance(value, Fuzzy):
            raise GologError(f"degree(V, C) takes a qualitative value such as dist(A, B), "
                             f"not {value!r}")
        return value.degree(str(category))

    theory.function("dist", dist)
    theory.function("orient", orient)
    theory.function("is", is_)
    theory.function("degree", degree)
