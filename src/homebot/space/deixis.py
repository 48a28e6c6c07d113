"""Pointing and "there": a pointing gesture picks a place on a surface (CAESAR Fig. 6).

A pointing gesture is a ``homebot.geometry.Ray`` from the shoulder (or the eyes)
through the hand (map frame, metres, z up), which meets the surface's plane at the
pointed point. ``pointed_place`` takes the named place the pointed point is closest
to, by the fuzzy ``closeness`` read in the surface's frame, and asks (returns None)
when two places are about as close or none is near. ``deictic_request`` reads "put
the red cup there".
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Final

from homebot.geometry import Ray
from homebot.space.distance import closeness

__all__ = ["deictic_request", "pointed_place"]

_REQUEST: Final = re.compile(
    r"^\s*(?:please\s+)?(?:put|place|set|move)\s+(?:the\s+)?(?P<what>[^\W\d][\w' -]*?)\s+"
    r"(?:there|over there|here)\s*(?:please)?\s*[.!]?\s*$", re.IGNORECASE)


def pointed_place(gesture: Ray, places: Mapping[str, tuple[float, float]], height: float,
                  scale: float, margin: float = 0.15) -> tuple[str | None, list[tuple[str, float]]]:
    """The place pointed at, and every place's closeness to the pointed point (best first).

    None when the gesture meets no plane, the best closeness is below 0.5 (pointing
    between or beyond the places), or the runner-up is within ``margin`` of it."""
    met = gesture.meets_height(height)
    if met is None:
        return None, []
    point = met[:2]
    scored = sorted(((name, closeness(math.dist(point, where), scale))
                     for name, where in places.items()), key=lambda pair: (-pair[1], pair[0]))
    best = scored[0][1]
    if best < 0.5 or (len(scored) > 1 and best - scored[1][1] < margin):
        return None, scored
    return scored[0][0], scored


def deictic_request(text: str) -> str | None:
    """What "put the red cup there" asks to put there (``red cup``); None for other words."""
    match = _REQUEST.match(text)
    return match["what"].strip().lower() if match else None
