"""Referring expressions on generated table tops: right object, or a question when it is close.

Each scene is a table (0.8–1.8 m by 0.6–1.0 m) seen from its front side, with 3–8
objects (cups, plates, bowls, bottles, glasses), at least two of the category
referred to. An expression is generated for a category with two or more members:
"the left cup", "the bottle behind the bowl", "the cup close to the plate", "the
glass far from the bottle", "the left cup close to the plate"... It is read by
``split_spatial`` (as the parser reads it) and resolved by ``resolve`` on
*perceived* positions: the true ones with Gaussian noise (``--noise``, metres).

The referent is what the speaker's fuzzy model says of the *true* positions: the
candidate with the highest degree; the truth margin is the gap between it and the
runner-up, as a share of its degree. A case is **close** when that gap is below
``--margin`` (the stated margin, also the resolver's), or when even the referent fits
the words poorly (degree below ``AT_LEAST``, 0.2: "the front cup" of cups standing
side by side), else **clear**. Figures:

- ``acceptable``: clear cases resolved to the referent, plus close cases resolved to
  the referent or to a question (the target is at least 95 %);
- ``confident_wrong_close``: close cases resolved to another object (the target is 0);
- ``weak``: the close cases in which even the referent fits poorly; ``fitting`` the
  others, and ``acceptable_fitting`` the share acceptable among them;
- ``confident_wrong``: all cases resolved to another object;
- ``clear_right``: the share of clear cases resolved to the referent (not a question);
- ``agrees_with_geometry``: for "the left/right X" and "the X close to R", how often
  the speaker's fuzzy referent is also the crisp one (largest lateral offset to that
  side; nearest to R): the fuzzy model checked against plain geometry;
- timing: ``scene_relations`` (all pairwise distance and orientation memberships) of a
  50-object scene, median of ``--repeats`` runs.
"""

from __future__ import annotations

import argparse
import math
import random
import statistics
import time
from collections import Counter
from dataclasses import dataclass
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import count, seed
from homebot.errors import BenchmarkError
from homebot.progress import track
from homebot.space.frames import Frame
from homebot.space.referring import AT_LEAST, MARGIN, Scene, degrees, resolve, split_spatial
from homebot.space.relations import scene_relations

__all__ = ["Case", "add_arguments", "generate_case", "run"]

CATEGORIES = ("cup", "plate", "bowl", "bottle", "glass")
_SIDES = ("left", "right", "front", "back")
_RELATIONS = {"close to": "near", "near": "near", "next to": "near", "far from": "far",
              "behind": "back", "in front of": "front", "left of": "left", "right of": "right"}
_SPACING = 0.07  #: objects stand at least this far apart (centre to centre, metres)
_EDGE = 0.05


@dataclass(frozen=True)
class Case:
    """One generated scene with its expression, what the speaker means, and the margin."""

    text: str
    noun: str
    points: dict[str, tuple[float, float]]
    categories: dict[str, str]
    scale: float
    viewer: tuple[float, float]
    facing: float
    candidates: list[str]
    referent: str
    gap: float
    best: float
    kind: str
    crisp: str | None  #: the plain-geometry referent, for side and near expressions


def _table(rng: random.Random) -> tuple[Frame, float, float, tuple[float, float]]:
    """A table frame (local x towards its front, y to its left), its width (along y) and
    depth (along x), and the viewer: 0.6 m before the front edge, facing the table."""
    width, depth = rng.uniform(0.8, 1.8), rng.uniform(0.6, 1.0)
    front = rng.choice((0.0, math.pi / 2, math.pi, -math.pi / 2))
    centre = (rng.uniform(-3, 3), rng.uniform(-3, 3))
    frame = Frame("table", "furniture", centre, front, math.hypot(width, depth))
    return frame, width, depth, frame.to_map((depth / 2 + 0.6, 0.0))


def _place(rng: random.Random, frame: Frame, width: float, depth: float,
           placed: list[tuple[float, float]]) -> tuple[float, float]:
    point = frame.origin
    for _ in range(200):
        local = (rng.uniform(-depth / 2 + _EDGE, depth / 2 - _EDGE),
                 rng.uniform(-width / 2 + _EDGE, width / 2 - _EDGE))
        point = frame.to_map(local)
        if all(math.dist(point, other) >= _SPACING for other in placed):
            break
    return point


def _expression(rng: random.Random, noun: str, others: list[str]) -> tuple[str, str]:
    """Text and kind of a referring expression for ``noun`` (relata among ``others``)."""
    kinds = ["side"] + (["relation", "side+relation"] if others else [])
    kind = rng.choice(kinds)
    side = rng.choice(_SIDES)
    if kind == "side":
        return (f"bring me the {side} {noun}" if rng.random() < 0.7 or side in ("front", "back")
                else f"bring me the {noun} on the {side}"), f"side:{side}"
    phrase = rng.choice(sorted(_RELATIONS))
    relatum = rng.choice(others)
    if kind == "relation":
        return f"bring me the {noun} {phrase} the {relatum}", f"relation:{_RELATIONS[phrase]}"
    near = rng.choice(("close to", "near"))
    side = rng.choice(("left", "right"))
    return f"bring me the {side} {noun} {near} the {relatum}", f"side:{side}+near"


def generate_case(rng: random.Random) -> Case:
    """One scene and expression; the referent by the speaker's model on the truth."""
    frame, width, depth, viewer = _table(rng)
    total = rng.randint(3, 8)
    noun = rng.choice(CATEGORIES)
    members = rng.randint(2, total)
    kinds = [noun] * members + [rng.choice([c for c in CATEGORIES if c != noun])
                                for _ in range(total - members)]
    points: dict[str, tuple[float, float]] = {}
    categories: dict[str, str] = {}
    numbering: Counter[str] = Counter()
    for category in kinds:
        numbering[category] += 1
        name = f"{category} {numbering[category]}"
        points[name] = _place(rng, frame, width, depth, list(points.values()))
        categories[name] = category
    others = sorted({c for c in kinds if c != noun})
    text, kind = _expression(rng, noun, others)
    _, modifiers = split_spatial(text)
    candidates = [name for name in points if categories[name] == noun]
    facing = frame.front + math.pi  # the viewer faces the table's front side
    scene = Scene(points, categories, frame.scale, viewer, facing)
    scored = degrees(candidates, modifiers, scene)
    crisp = _crisp(kind, modifiers[-1].relatum if modifiers else None, scene, candidates, frame)
    best, second = scored[0][1], scored[1][1]
    return Case(text, noun, points, categories, frame.scale, viewer, facing, candidates,
                scored[0][0],
                (best - second) / best if best > 0 else 0.0, best, kind, crisp)


def _crisp(kind: str, relatum: str | None, scene: Scene, candidates: list[str],
           frame: Frame) -> str | None:
    """Plain geometry's referent: the largest lateral offset to a side, the nearest to R."""
    if kind in ("side:left", "side:right"):
        sign = 1.0 if kind == "side:left" else -1.0  # the viewer faces the table: its left
        return max(candidates, key=lambda name: sign * -frame.to_local(scene.points[name])[1])
    if kind == "relation:near" and relatum is not None:
        relata = [n for n, c in scene.categories.items() if c == relatum]
        return min(candidates, key=lambda name: min(
            math.dist(scene.points[name], scene.points[r]) for r in relata))
    return None


def _between(option: str, low: float, high: float) -> Any:
    """An argument type for ``option``: a number from ``low`` to ``high``."""
    def number(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not low <= value <= high:  # also false for nan
            raise BenchmarkError(f"{option} {text!r}: give a number from {low:g} to {high:g}")
        return value
    number.__name__ = option.lstrip("-")
    return number


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--scenes", type=count("--scenes", 1, 1_000_000), default=1000,
                        help="generated table-top scenes (at least 200 for the figure)")
    parser.add_argument("--seed", type=seed, default=0, help="seed of the first scene")
    parser.add_argument("--noise", type=_between("--noise", 0.0, 0.5), default=0.01,
                        help="perception noise: standard deviation of positions, metres")
    parser.add_argument("--margin", type=_between("--margin", 0.01, 0.99), default=MARGIN,
                        help="the stated margin: closer degrees are 'about equal'")
    parser.add_argument("--repeats", type=count("--repeats", 1, 100_000), default=200,
                        help="timed runs of the 50-object scene")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Resolve ``--scenes`` generated expressions; time a 50-object scene's relations."""
    rng = random.Random(args.seed)
    tally: Counter[str] = Counter()
    fitting: Counter[str] = Counter()  #: the cases whose referent fits the words (not weak)
    by_kind: dict[str, Counter[str]] = {}
    agree = total_crisp = 0
    for _ in track(range(args.scenes), "referring expressions"):
        case = generate_case(rng)
        _, modifiers = split_spatial(case.text)
        seen = {name: (x + rng.gauss(0, args.noise), y + rng.gauss(0, args.noise))
                for name, (x, y) in case.points.items()}
        answer = resolve(case.candidates, modifiers,
                         Scene(seen, case.categories, case.scale, case.viewer, case.facing),
                         noun=case.noun, margin=args.margin)
        close = case.gap < args.margin or case.best < AT_LEAST
        tally["weak"] += case.best < AT_LEAST
        weak = case.best < AT_LEAST
        if answer.referent == case.referent:
            verdict = "right"
        elif answer.referent is None:
            verdict = "question"
        else:
            verdict = "wrong"
        label = f"{'close' if close else 'clear'}_{verdict}"
        tally[label] += 1
        if not weak:
            fitting[label] += 1
        by_kind.setdefault(case.kind.split("+")[0].split(":")[0] + (
            "+near" if "+" in case.kind else ""), Counter())[label] += 1
        if case.crisp is not None:
            total_crisp += 1
            agree += case.crisp == case.referent
    scenes = args.scenes
    acceptable = tally["clear_right"] + tally["close_right"] + tally["close_question"]
    timing = _timing(args.repeats)
    figures: dict[str, Any] = {
        "benchmark": "referring", "scenes": scenes, "seed": args.seed, "noise_m": args.noise,
        "margin": args.margin,
        "clear": tally["clear_right"] + tally["clear_question"] + tally["clear_wrong"],
        "close": tally["close_right"] + tally["close_question"] + tally["close_wrong"],
        "weak": tally["weak"],
        "outcomes": {key: value for key, value in sorted(tally.items()) if key != "weak"},
        "acceptable": round(acceptable / scenes, 4),
        "fitting": sum(fitting.values()),
        "acceptable_fitting": round((fitting["clear_right"] + fitting["close_right"] + fitting[
            "close_question"]) / max(1, sum(fitting.values())), 4),
        "clear_right": round(tally["clear_right"] / max(1, tally["clear_right"] + tally[
            "clear_question"] + tally["clear_wrong"]), 4),
        "confident_wrong_close": tally["close_wrong"],
        "confident_wrong": tally["clear_wrong"] + tally["close_wrong"],
        "by_kind": {kind: dict(sorted(counts.items())) for kind, counts in sorted(
            by_kind.items())},
        "agrees_with_geometry": round(agree / total_crisp, 4) if total_crisp else None,
        "geometry_cases": total_crisp,
        **timing,
    }
    if console is not None:
        _print(console, figures)
    return figures


def _timing(repeats: int) -> dict[str, Any]:
    rng = random.Random(50)
    points = {f"object {index}": (rng.uniform(0, 5), rng.uniform(0, 4)) for index in range(50)}
    times = []
    for _ in range(repeats):
        began = time.perf_counter()
        relations = scene_relations(points, math.hypot(5, 4), viewer=(2.5, -1.0))
        times.append(time.perf_counter() - began)
    assert relations.distances.shape == (50, 50)
    return {"relations_50_objects_ms_median": round(statistics.median(times) * 1000, 3),
            "relations_50_objects_ms_max": round(max(times) * 1000, 3),
            "relations_pairs": 50 * 49}


def _print(console: Console, figures: dict[str, Any]) -> None:
    table = Table(title=f"referring expressions: {figures['scenes']} scenes, noise "
                        f"{figures['noise_m']} m, margin {figures['margin']}")
    table.add_column("figure")
    table.add_column("value", justify="right")
    for key in ("clear", "close", "weak", "acceptable", "fitting", "acceptable_fitting",
                "clear_right", "confident_wrong_close", "confident_wrong", "agrees_with_geometry",
                "relations_50_objects_ms_median", "relations_50_objects_ms_max"):
        table.add_row(key, str(figures[key]))
    for kind, counts in figures["by_kind"].items():
        table.add_row(f"  {kind}", ", ".join(f"{k} {v}" for k, v in counts.items()))
    console.print(table)
