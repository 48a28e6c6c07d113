"""Referring expressions: "the left cup", "the cup close to the plate", resolved by fuzzy degrees.

``split_spatial(text)`` finds the spatial modifiers of a command and returns the
text without them, so the parser reads "bring me the cup" and records the
modifiers on the object reference. ``resolve(candidates, modifiers, scene)`` then
picks the one candidate the modifiers fit best, or asks when two fit about
equally (the runner-up's degree within ``margin`` of the best, as a share of the
best) or none fits.

Degrees, each from 0 to 1, combined by product (a t-norm):

- **side** ("the left cup", "the cup on the right", "the front cup"): the candidate
  lies to that side of *every other* candidate, as the viewer sees it: the least
  ``side_degree`` over the others. Only the leftmost cup has a degree above 0; when
  another cup stands nearly straight behind it, its degree is small and the robot
  asks.
- **near** ("close to", "near", "next to", "beside"): ``closeness`` of the distance
  to the relatum in the scene's frame; **far** ("far from") its complement;
- **direction** ("behind", "in front of", "left of", "right of" the relatum):
  ``side_degree`` of the direction from the relatum, times ``closeness`` (the
  bottle behind the bowl is behind it *and* near it).

The relatum ("the plate") is any other thing in the scene whose category or name
is that word; with several, the best fitting one counts. A relatum with a front side
(furniture, ``Scene.fronts``) is read intrinsically: "behind the couch" is the side
away from where the couch faces, wherever the viewer stands.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Final

from homebot.space.distance import closeness
from homebot.space.orientation import intrinsic_angle, relative_angle, side_degree

__all__ = [
    "AT_LEAST",
    "MARGIN",
    "Modifier",
    "Resolution",
    "Scene",
    "degrees",
    "modifiers_from",
    "resolve",
    "split_spatial",
]

#: two candidates whose degrees differ by less than this share of the best fit "about
#: equally": ask
MARGIN: Final = 0.15
#: a best degree below this fits not at all: ask
AT_LEAST: Final = 0.2

_SIDES: Final = {"left": "left", "leftmost": "left", "right": "right", "rightmost": "right",
                 "front": "front", "frontmost": "front", "back": "back", "rear": "back",
                 "backmost": "back"}
_RELATIONS: Final = {
    "close to": "near", "near to": "near", "near": "near", "next to": "near",
    "beside": "near", "far from": "far", "far away from": "far", "behind": "back",
    "in front of": "front", "to the left of": "left", "left of": "left",
    "on the left of": "left", "to the right of": "right", "right of": "right",
    "on the right of": "right",
}
_STOP: Final = r"(?=$|[,.;!?]|\s(?:on|in|at|to|from|and|then|please|for|into|onto|with|of)\b)"
_RELATION_RE: Final = re.compile(
    r"\s+(?:(?:which|that) (?:is|are|stands|lies)\s+)?"
    r"(?P<rel>" + "|".join(sorted((re.escape(k) for k in _RELATIONS), key=len, reverse=True))
    + r")\s+(?:the|a|an|my|your)\s+(?P<relatum>[^\W\d][\w' -]*?)" + _STOP, re.IGNORECASE)
_SIDE_BEFORE_RE: Final = re.compile(
    r"(?<!\bto )(?<!\bon )(?<!\bat )\b(?P<det>the|that)\s+(?P<side>" + "|".join(_SIDES)
    + r")\s+(?!(?:arm|arms|hand|hands|leg|side|in|on|at|of|to|and|then|or)\b)(?=[^\W\d])",
    re.IGNORECASE)
_SIDE_AFTER_RE: Final = re.compile(r"\s+(?:(?:which|that) is\s+)?on the (?P<side>left|right)\b"
                                   r"(?!\s+of\b)", re.IGNORECASE)


@dataclass(frozen=True, slots=True)
class Modifier:
    """One spatial modifier: ``side`` (of the candidates themselves) or a relation
    (``near``, ``far``, ``back``, ``front``, ``left``, ``right``) to a ``relatum``."""

    kind: str  #: "side" or "relation"
    value: str
    relatum: str | None = None
    text: str = ""

    def to_dict(self) -> dict[str, str]:
        data = {"kind": self.kind, "value": self.value, "text": self.text}
        if self.relatum is not None:
            data["relatum"] = self.relatum
        return data

    @classmethod
    def from_dict(cls, data: Mapping[str, str]) -> Modifier:
        return cls(data["kind"], data["value"], data.get("relatum"), data.get("text", ""))


def modifiers_from(data: Any) -> list[Modifier]:
    """Modifiers as a task step gives them: a list of ``Modifier.to_dict`` mappings or of
    phrases ("left", "close to the plate"), or one phrase. Raises ``ValueError`` saying
    what is wrong for anything else."""
    items = [data] if isinstance(data, str | Mapping) else data
    if not isinstance(items, list | tuple) or not items:
        raise ValueError(f"spatial modifiers are a list such as [left, close to the plate], "
                         f"not {data!r}")
    found: list[Modifier] = []
    for item in items:
        if isinstance(item, str):
            phrase = split_spatial(f"the one {item}")[1] or split_spatial(f"the {item} one")[1]
            if not phrase:
                raise ValueError(f"'{item}' is no spatial modifier; say e.g. left, behind the "
                                 "bowl, close to the plate")
            found += phrase
        elif isinstance(item, Mapping) and item.get("kind") in ("side", "relation") and (
                isinstance(item.get("value"), str)):
            found.append(Modifier.from_dict({str(k): str(v) for k, v in item.items()}))
        else:
            raise ValueError(f"{item!r} is no spatial modifier; give a phrase such as 'left'")
    return found


def split_spatial(text: str) -> tuple[str, list[Modifier]]:
    """The command without its spatial modifiers, and the modifiers in the order said."""
    found: list[tuple[int, Modifier]] = []

    def relation(match: re.Match[str]) -> str:
        found.append((match.start(), Modifier(
            "relation", _RELATIONS[match["rel"].lower()], match["relatum"].strip().lower(),
            match.group(0).strip())))
        return ""

    def side_before(match: re.Match[str]) -> str:
        found.append((match.start(), Modifier("side", _SIDES[match["side"].lower()],
                                              text=match.group(0).strip())))
        return f"{match['det']} "

    def side_after(match: re.Match[str]) -> str:
        found.append((match.start(), Modifier("side", match["side"].lower(),
                                              text=match.group(0).strip())))
        return ""

    rest = _RELATION_RE.sub(relation, text)
    rest = _SIDE_AFTER_RE.sub(side_after, rest)
    rest = _SIDE_BEFORE_RE.sub(side_before, rest)
    return re.sub(r"\s{2,}", " ", rest).strip(), [modifier for _, modifier in found]


@dataclass(frozen=True)
class Scene:
    """What the robot knows of a scene: where things are (map frame), what they are,
    the frame's scale, and the viewer whose left is "left"."""

    points: Mapping[str, tuple[float, float]]
    categories: Mapping[str, str]
    scale: float
    viewer: tuple[float, float]
    #: the viewer's heading; None: the line of sight to each relatum in turn
    facing: float | None = None
    #: front headings of relata that have a front side (furniture): "behind the sofa" is
    #: read against the sofa's own front (intrinsic), not the viewer's
    fronts: Mapping[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Resolution:
    """The referent, or the question to ask; ``degrees`` of every candidate, best first."""

    referent: str | None
    question: str | None
    degrees: list[tuple[str, float]] = field(default_factory=list)

    def __bool__(self) -> bool:
        return self.referent is not None


def _relata(scene: Scene, word: str, exclude: str) -> list[str]:
    word = word.lower().strip()
    return [name for name in scene.points if name != exclude and (
        name.lower() == word or scene.categories.get(name, "").lower() == word
        or name.lower().endswith(f" {word}"))]


def _degree(candidate: str, others: Sequence[str], modifier: Modifier, scene: Scene) -> float:
    here = scene.points[candidate]
    if modifier.kind == "side":
        if not others:
            return 1.0
        return min(side_degree(relative_angle(here, scene.points[other], scene.viewer,
                                              scene.facing), modifier.value)
                   for other in others)
    relata = _relata(scene, modifier.relatum or "", candidate)
    best = 0.0
    for relatum in relata:
        there = scene.points[relatum]
        near = closeness(math.dist(here, there), scene.scale)
        if modifier.value == "near":
            value = near
        elif modifier.value == "far":
            value = 1.0 - near
        else:
            front = scene.fronts.get(relatum)
            angle = intrinsic_angle(here, there, front) if front is not None else (
                relative_angle(here, there, scene.viewer, scene.facing))
            value = side_degree(angle, modifier.value) * near
        best = max(best, value)
    return best


def degrees(candidates: Sequence[str], modifiers: Sequence[Modifier],
            scene: Scene) -> list[tuple[str, float]]:
    """Each candidate's degree of fitting all ``modifiers``, best first (ties by name)."""
    scored = []
    for candidate in candidates:
        others = [other for other in candidates if other != candidate]
        value = 1.0
        for modifier in modifiers:
            value *= _degree(candidate, others, modifier, scene)
        scored.append((candidate, value))
    return sorted(scored, key=lambda pair: (-pair[1], pair[0]))


def resolve(candidates: Sequence[str], modifiers: Sequence[Modifier], scene: Scene, *,
            noun: str = "one", margin: float = MARGIN) -> Resolution:
    """The candidate the modifiers fit best, or a question when the runner-up's degree is
    within ``margin`` (a share of the best degree) of the best, or nothing fits (missing
    relatum, degrees near 0)."""
    if not candidates:
        return Resolution(None, f"I see no {noun} here.")
    for modifier in modifiers:
        if modifier.kind == "relation" and not any(
                _relata(scene, modifier.relatum or "", c) for c in candidates):
            return Resolution(None, f"I see no {modifier.relatum} here. Which {noun} do you "
                                    "mean?")
    scored = degrees(candidates, modifiers, scene)
    best_name, best = scored[0]
    if best < AT_LEAST:  # nothing fits the words well: name the likeliest few
        return Resolution(None, _which(noun, [name for name, _ in scored[:3]]), scored)
    close = [name for name, value in scored if best - value < margin * best]
    if len(close) > 1:
        return Resolution(None, _which(noun, close), scored)
    return Resolution(best_name, None, scored)


def _which(noun: str, names: Sequence[str]) -> str:
    if len(names) == 1:
        return f"Do you mean the {names[0]}?"
    listed = ", ".join(f"the {name}" for name in names[:-1]) + f" or the {names[-1]}"
    return f"Which {noun} do you mean: {listed}?"
