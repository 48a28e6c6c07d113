"""Dynamic gestures from the hand's trajectory: the $1 unistroke recogniser (CAESAR §2.4).

CAESAR read dynamic gestures with the $1 recogniser (Wobbrock, Wilson and Li 2007):
a stroke is resampled to ``POINTS`` points evenly spaced along its path, scaled
into a reference square, moved to the origin, and matched against templates by
the mean distance between corresponding points at the best rotation (golden
section search). Here the stroke is the hand's path over a burst of frames,
projected into the person's frontal plane (their right and up, as they face the
robot). Two departures from $1, both to keep directions apart: a swipe to the
left and one to the right are the same line turned half round, so the rotation is
searched within ``_ROTATION`` only, not normalised away; and the scaling is
uniform (by the larger side), which keeps a straight swipe straight ($1's
non-uniform scaling blows a line up into noise across it).

The templates are drawn, not recorded: circles (either way round, from any start,
one to three loops), swipes left and right, beckoning (the hand brought up towards
the face and down again) and waving (side to side), both from any point of a
swing, two to eight swings: a look catches a periodic gesture anywhere in it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["DYNAMIC_GESTURES", "POINTS", "StrokeRecogniser", "frontal_stroke", "normalise"]

DYNAMIC_GESTURES = ("circle", "swipe_left", "swipe_right", "beckon", "wave")
POINTS = 64  #: points a stroke is resampled to
_SIZE = 1.0  #: the reference square's side
_ROTATION = math.radians(30.0)  #: searched either way round (directions matter)
_PRECISION = math.radians(2.0)  #: the golden section search's stopping width
_PHI = 0.5 * (-1.0 + math.sqrt(5.0))
_MIN_EXTENT = 0.15  #: metres the hand's path spans in a dynamic gesture (less: held still)
_JUMP = 0.3  #: metres between two frames' hands: the hand was lost in between
_MIN_SCORE = 0.75  #: $1's score (1: a template's exact shape) a stroke must reach


@dataclass(frozen=True)
class _Template:
    name: str
    points: np.ndarray  #: (POINTS, 2), normalised


def frontal_stroke(hands: np.ndarray, head: np.ndarray, robot: tuple[float, float]
                   ) -> np.ndarray:
    """The hand's path (n, 3; map frame) in the frontal plane of a person whose head is
    at ``head`` facing the robot at ``robot``: (n, 2) metres to their right and up."""
    facing = np.array([robot[0] - head[0], robot[1] - head[1]])
    facing /= max(float(np.linalg.norm(facing)), 1e-9)
    their_right = np.array([facing[1], -facing[0]])
    return np.column_stack((hands[:, :2] @ their_right, hands[:, 2]))


def normalise(stroke: np.ndarray) -> np.ndarray | None:
    """$1's steps but the rotation: resampled, scaled uniformly into the reference square,
    centred; None for a stroke with no length."""
    points = _resample(np.asarray(stroke, dtype=float))
    if points is None:
        return None
    extent = float(np.ptp(points, axis=0).max())
    if extent < 1e-9:
        return None
    points = points * (_SIZE / extent)
    centred: np.ndarray = points - points.mean(axis=0)
    return centred


class StrokeRecogniser:
    """Names a stroke by the nearest of the drawn templates ($1)."""

    def __init__(self) -> None:
        self.templates = [_Template(name, normalised) for name, stroke in _drawn_templates()
                          if (normalised := normalise(stroke)) is not None]

    def read(self, track: np.ndarray, robot: tuple[float, float]) -> str | None:
        """The dynamic gesture in arm keypoints (frames, 4, 3: head, shoulder, elbow, hand;
        map frame, as ``body_parts.arm_track`` gives them) of a person facing the robot at
        ``robot``; None when the hand draws none of them."""
        track = np.asarray(track, dtype=float)
        stroke = frontal_stroke(track[:, 3], track[:, 0].mean(axis=0), robot)
        # where the hand jumps, it was lost in between (a swipe's arm dropped and raised
        # again): the stroke is the widest unbroken piece
        jumps = np.flatnonzero(np.linalg.norm(np.diff(stroke, axis=0), axis=1) > _JUMP) + 1
        pieces = np.split(stroke, jumps)
        widest = max(pieces, key=lambda piece: float(np.ptp(piece, axis=0).max()))
        return self.recognise(widest)[0]

    def recognise(self, stroke: np.ndarray) -> tuple[str | None, float]:
        """The gesture a stroke (n, 2; right and up, metres) is, and $1's score; None when
        the hand hardly moved or no template is near enough."""
        stroke = np.asarray(stroke, dtype=float)
        if len(stroke) < 2 or float(np.ptp(stroke, axis=0).max()) < _MIN_EXTENT:
            return None, 0.0
        points = normalise(stroke)
        if points is None:
            return None, 0.0
        best, name = math.inf, None
        for template in self.templates:
            distance = _distance_at_best_angle(points, template.points)
            if distance < best:
                best, name = distance, template.name
        score = 1.0 - best / (0.5 * math.sqrt(2.0) * _SIZE)
        return (name if score >= _MIN_SCORE else None), score


def _resample(stroke: np.ndarray) -> np.ndarray | None:
    """``POINTS`` points evenly spaced along the stroke's path."""
    steps = np.linalg.norm(np.diff(stroke, axis=0), axis=1)
    along = np.concatenate(([0.0], np.cumsum(steps)))
    if along[-1] < 1e-9:
        return None
    wanted = np.linspace(0.0, along[-1], POINTS)
    return np.column_stack([np.interp(wanted, along, stroke[:, axis]) for axis in range(2)])


def _rotated(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    turned: np.ndarray = points @ np.array([[c, s], [-s, c]])
    return turned


def _distance_at_best_angle(points: np.ndarray, template: np.ndarray) -> float:
    """$1's golden section search for the rotation (within ``_ROTATION``) that brings the
    stroke nearest the template: the mean distance between corresponding points there."""
    def distance(angle: float) -> float:
        return float(np.mean(np.linalg.norm(_rotated(points, angle) - template, axis=1)))

    low, high = -_ROTATION, _ROTATION
    x1 = _PHI * low + (1 - _PHI) * high
    x2 = (1 - _PHI) * low + _PHI * high
    f1, f2 = distance(x1), distance(x2)
    while abs(high - low) > _PRECISION:
        if f1 < f2:
            high, x2, f2 = x2, x1, f1
            x1 = _PHI * low + (1 - _PHI) * high
            f1 = distance(x1)
        else:
            low, x1, f1 = x1, x2, f2
            x2 = (1 - _PHI) * low + _PHI * high
            f2 = distance(x2)
    return min(f1, f2)


def _drawn_templates() -> list[tuple[str, np.ndarray]]:
    """Each gesture's strokes as people make them, in the frontal plane (right, up)."""
    templates: list[tuple[str, np.ndarray]] = []
    turn = np.linspace(0.0, 1.0, 200)
    for loops in np.arange(1.0, 3.01, 0.25):
        for start in np.arange(8) * math.pi / 4:
            for way in (1.0, -1.0):
                angle = start + way * 2 * math.pi * loops * turn
                templates.append(("circle", np.column_stack((np.cos(angle), np.sin(angle)))))
    line = np.linspace(-1.0, 1.0, 50)
    for bow in (0.0, 0.1, -0.1):  # a swipe bows up or down a little
        arc = bow * (1.0 - line ** 2)
        templates.append(("swipe_right", np.column_stack((line, arc))))
        templates.append(("swipe_left", np.column_stack((-line, arc))))
    # to and fro along a line, from any point of a swing, 2 to 8 swings: beckoning is
    # up and down, waving side to side
    for cycles in np.arange(2.0, 8.01, 0.25):
        for start in np.arange(8) / 8:
            swing = np.sin(2 * math.pi * (start + np.linspace(0.0, cycles, 200)))
            flat = np.zeros_like(swing)
            templates.append(("beckon", np.column_stack((flat, swing))))
            templates.append(("wave", np.column_stack((swing, flat))))
    return templates
