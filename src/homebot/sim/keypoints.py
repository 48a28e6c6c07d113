"""Arm keypoints of a person making a gesture, as a depth camera's body segmentation gives them.

Each frame holds four points in the map frame (metres, z up): head, shoulder,
elbow and hand of the gesturing arm (Cosero §7.1.3 finds the same four). The
person stands at a place facing the robot and points at a target (the eye-hand
line aims at it, with a few degrees of aiming error), waves (the raised hand
swings from side to side), shows stop (a raised open hand held out towards the
robot), raises the arm straight up, or stands with the arm hanging. Every point
carries Gaussian noise. Deterministic by seed.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["GESTURES", "gesture_keypoints"]

GESTURES = ("pointing", "waving", "stop", "raising", "none")
_HEIGHT = 1.75  #: metres: the person the proportions below are for
_HEAD = 1.62  #: metres
_SHOULDER = (0.19, 1.42)  #: sideways from the head's axis, height
_UPPER, _FORE = 0.30, 0.32  #: arm segment lengths, metres


def gesture_keypoints(gesture: str, person: tuple[float, float], robot: tuple[float, float],
                      rng: np.random.Generator, *, target: tuple[float, float, float] | None = None,
                      seconds: float = 1.5, rate: float = 15.0, noise: float = 0.02,
                      aim: float = 0.03, side: str | None = None,
                      height: float = 1.75) -> np.ndarray:
    """Keypoints (frames, 4, 3): head, shoulder, elbow, hand, over ``seconds``.

    ``target`` is where a pointing gesture aims (map frame); ``aim`` the standard
    deviation of the aiming error in radians, ``noise`` the keypoints' in metres.
    ``side`` is the arm, the person's ``left`` or ``right`` (None: either, at random);
    ``height`` the person's, which places their head and shoulders.
    """
    if gesture not in GESTURES:
        raise ValueError(f"unknown gesture {gesture!r}; one of {', '.join(GESTURES)}")
    facing = math.atan2(robot[1] - person[1], robot[0] - person[0])
    forward = np.array([math.cos(facing), math.sin(facing), 0.0])
    right = np.array([math.sin(facing), -math.cos(facing), 0.0])
    chosen = side if side is not None else ("right" if rng.random() < 0.5 else "left")
    if chosen not in ("left", "right"):
        raise ValueError(f"unknown side {side!r}; left or right")
    # facing the robot, the person's right hand is on the robot's left ("right" vector)
    side_sign = 1.0 if chosen == "right" else -1.0
    scale = height / _HEIGHT
    head = np.array([person[0], person[1], _HEAD * scale])
    shoulder = head + side_sign * _SHOULDER[0] * right
    shoulder[2] = _SHOULDER[1] * scale
    frames = round(seconds * rate)
    times = np.arange(frames) / rate
    hands = np.empty((frames, 3))
    elbows = np.empty((frames, 3))
    if gesture == "pointing":
        if target is None:
            raise ValueError("a pointing gesture needs a target")
        ray = np.asarray(target, dtype=float) - head
        ray /= np.linalg.norm(ray)
        ray = _perturb(ray, aim, rng)
        # the hand on the eye-target line, an arm's length from the shoulder
        hand = _on_ray(head, ray, shoulder, _UPPER + _FORE - 0.02)
        hands[:] = hand
        elbows[:] = shoulder + (hand - shoulder) * 0.48 - np.array([0, 0, 0.03])
    elif gesture == "stop":
        hand = shoulder + 0.45 * forward + np.array([0.0, 0.0, 0.25])
        hands[:] = hand
        elbows[:] = shoulder + 0.22 * forward + np.array([0.0, 0.0, 0.05])
    elif gesture == "raising":
        elbows[:] = shoulder + np.array([0.0, 0.0, _UPPER]) + 0.04 * side_sign * right
        hands[:] = elbows + np.array([0.0, 0.0, _FORE]) + 0.02 * forward
    elif gesture == "waving":
        beat = rng.uniform(1.5, 2.5)  # waves a second
        swing = 0.15 * np.sin(2 * math.pi * beat * times + rng.uniform(0, 2 * math.pi))
        elbow = shoulder + 0.12 * forward + side_sign * 0.18 * right - np.array([0.0, 0.0, 0.12])
        elbows[:] = elbow
        hands[:] = elbow + np.array([0.0, 0.0, 0.28]) + swing[:, None] * right[None, :]
    else:
        elbows[:] = shoulder - np.array([0.0, 0.0, _UPPER]) + 0.03 * forward
        hands[:] = elbows - np.array([0.0, 0.0, _FORE]) + 0.06 * forward
    heads = np.repeat(head[None, :], frames, axis=0)
    shoulders = np.repeat(shoulder[None, :], frames, axis=0)
    points = np.stack((heads, shoulders, elbows, hands), axis=1)
    noisy: np.ndarray = points + rng.normal(0.0, noise, points.shape)
    return noisy


def _perturb(direction: np.ndarray, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """``direction`` turned by a small random angle (radians, standard deviation ``sigma``)."""
    turned = direction + rng.normal(0.0, sigma, 3)
    unit: np.ndarray = turned / np.linalg.norm(turned)
    return unit


def _on_ray(origin: np.ndarray, ray: np.ndarray, centre: np.ndarray, radius: float
            ) -> np.ndarray:
    """The point of the ray from ``origin`` at ``radius`` from ``centre`` (the far one)."""
    offset = origin - centre
    b = float(offset @ ray)
    c = float(offset @ offset) - radius ** 2
    along = -b + math.sqrt(max(b * b - c, 0.0))
    point: np.ndarray = origin + along * ray
    return point
