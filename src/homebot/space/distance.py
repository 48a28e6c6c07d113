"""Fuzzy qualitative distance: five overlapping categories, scaled by a frame (CAESAR Fig. 10a).

A distance ``d`` is read in the frame it is measured in: ``d / scale``, where the
scale is the frame's maximum distance (a table's diagonal, a room's). The five
categories, nearest first, are ``very_close``, ``close``, ``medium``, ``far`` and
``very_far``. Each category's membership peaks (1) at its centre and falls linearly
to 0 at its neighbours' centres (``very_close`` is full at 0, ``very_far`` from the
frame's maximum distance on), so:

- neighbouring categories overlap, and the memberships of every distance sum to 1
  (a fuzzy partition): at most two categories hold at once;
- at a boundary, halfway between two centres, the two neighbours hold with 0.5 each;
- the memberships depend on ``d / scale`` only: "close" on a 1.4 m table is a
  tenth of "close" in a 14 m room.

Centres sit at 0, 10 %, 25 %, 50 % and 100 % of the frame's maximum distance, so
the boundaries are at 5 %, 17.5 %, 37.5 % and 75 %: each category about twice as
wide as the one before, as in the paper's figure.
"""

from __future__ import annotations

import itertools
from typing import Final

__all__ = [
    "BOUNDARIES",
    "CENTRES",
    "DISTANCES",
    "at_most",
    "closeness",
    "distance_category",
    "distance_memberships",
    "is_distance",
]

#: the categories, nearest first
DISTANCES: Final = ("very_close", "close", "medium", "far", "very_far")
#: where each category holds fully, as shares of the frame's maximum distance
CENTRES: Final = (0.0, 0.10, 0.25, 0.50, 1.0)
#: where neighbouring categories meet (both hold 0.5), halfway between centres
BOUNDARIES: Final = tuple((low + high) / 2 for low, high in itertools.pairwise(CENTRES))
#: the graded value of each category for "close to" (1: very close ... 0: very far)
_CLOSENESS: Final = (1.0, 0.75, 0.5, 0.25, 0.0)


def _check(scale: float) -> None:
    if not scale > 0:
        raise ValueError(f"a frame's scale must be greater than 0, not {scale!r}")


def distance_memberships(distance: float, scale: float = 1.0) -> tuple[float, ...]:
    """The membership of ``distance`` (metres, at least 0) in each category of ``DISTANCES``."""
    _check(scale)
    ratio = max(distance, 0.0) / scale
    degrees = [0.0] * len(DISTANCES)
    for index in range(len(CENTRES) - 1):
        low, high = CENTRES[index], CENTRES[index + 1]
        if ratio < high:
            beyond = (ratio - low) / (high - low)
            degrees[index], degrees[index + 1] = 1.0 - beyond, beyond
            return tuple(degrees)
    degrees[-1] = 1.0
    return tuple(degrees)


def is_distance(distance: float, category: str, scale: float = 1.0) -> float:
    """The degree to which ``distance`` is ``category`` (``is(dist(A, B), close)``)."""
    if category not in DISTANCES:
        raise ValueError(f"unknown distance category {category!r}; one of {', '.join(DISTANCES)}")
    return distance_memberships(distance, scale)[DISTANCES.index(category)]


def at_most(distance: float, category: str, scale: float = 1.0) -> float:
    """The degree to which ``distance`` is ``category`` or nearer ("within close")."""
    if category not in DISTANCES:
        raise ValueError(f"unknown distance category {category!r}; one of {', '.join(DISTANCES)}")
    degrees = distance_memberships(distance, scale)
    return sum(degrees[: DISTANCES.index(category) + 1])


def distance_category(distance: float, scale: float = 1.0) -> str:
    """The category ``distance`` belongs to most (the nearer one on a boundary)."""
    degrees = distance_memberships(distance, scale)
    return DISTANCES[max(range(len(degrees)), key=lambda index: (degrees[index], -index))]


def closeness(distance: float, scale: float = 1.0) -> float:
    """How close, from 1 (very close) to 0 (very far): the categories' values weighted by
    their memberships. It falls strictly from 0 to the frame's maximum distance, then
    stays 0."""
    degrees = distance_memberships(distance, scale)
    return sum(degree * value for degree, value in zip(degrees, _CLOSENESS, strict=True))
