"""Gestures from arm keypoints: pointing, waving and stop (Cosero §7.1.3, CAESAR §2.4).

The input is a short window of frames, each with the head, shoulder, elbow and
hand of one arm (map frame, metres, z up), as a depth camera's body
segmentation gives them.

- **pointing**: the arm is stretched out (hand far from the shoulder), the hand
  held still, and it does not reach towards the robot. The pointing ray runs
  from the head (the eyes) through the hand: for distant targets the eye-hand
  line is the better aim. It is returned as a ``homebot.geometry.Ray``, as the
  symbolic world's pointing (``homebot.space.deixis``) takes it, and ``pointed_target``
  intersects it with placement tops and objects.
- **waving**: the hand, raised above the shoulder, swings from side to side: its
  sideways position over the window spreads and crosses its mean several times.
- **stop**: a raised open hand held out towards the robot, still.
- **raising**: the hand held still well above the head, the arm near vertical.

``person_gesture`` names what a person does as the world's people are described:
``raising_left_arm``, ``pointing_right`` and so on, left and right being the
person's own, who faces the robot. ``gesture_from_depth`` reads it from a burst of
head-camera frames: the keypoints come from the depth image (``perception.body_parts``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from homebot.geometry import Point3, Pose, Ray, nearest_by_angle
from homebot.perception.body_parts import arm_track
from homebot.robot import RgbdFrame

__all__ = [
    "Surface",
    "classify_gesture",
    "gesture_from_depth",
    "person_gesture",
    "pointed_object",
    "pointed_target",
    "pointing_ray",
]

_STRETCHED = 0.45  #: metres from shoulder to hand: an extended arm
_STILL = 0.06  #: metres: the hand's spread when held still
_WAVE_SPREAD = 0.05  #: metres: the raised hand's sideways spread when waving
_WAVE_CROSSINGS = 3
_TOWARDS = math.radians(35.0)  #: the arm within this of the line to the robot reaches to it
_ABOVE_HEAD = 0.12  #: metres the hand of a raised arm is above the head


@dataclass(frozen=True, slots=True)
class Surface:
    """A placement's top: axis-aligned footprint (centre, size) at a height, metres."""

    center: tuple[float, float]
    size: tuple[float, float]
    height: float


def classify_gesture(frames: np.ndarray, robot: tuple[float, float]) -> str:
    """``pointing``, ``waving``, ``stop`` or ``none`` for keypoint frames (n, 4, 3):
    head, shoulder, elbow, hand; ``robot`` is where the robot stands on the map."""
    frames = np.asarray(frames, dtype=float)
    head, shoulder, hand = (frames[:, index].mean(axis=0) for index in (0, 1, 3))
    hands = frames[:, 3]
    raised = hand[2] > shoulder[2] + 0.05
    # waving: sideways (across the line to the robot) swing of the raised hand
    to_robot = np.array([robot[0] - head[0], robot[1] - head[1]])
    to_robot /= max(float(np.linalg.norm(to_robot)), 1e-9)
    across = np.array([-to_robot[1], to_robot[0]])
    sideways = hands[:, :2] @ across
    sideways = sideways - sideways.mean()
    crossings = int(np.count_nonzero(np.diff(np.sign(sideways)) != 0))
    if raised and float(sideways.std()) > _WAVE_SPREAD and crossings >= _WAVE_CROSSINGS:
        return "waving"
    still = float(np.linalg.norm(hands.std(axis=0))) < _STILL
    arm = hand - shoulder
    reach = float(np.linalg.norm(arm))
    if not still or reach < 0.3:
        return "none"
    flat = float(np.linalg.norm(arm[:2]))
    towards = flat > 1e-6 and math.acos(max(-1.0, min(1.0, float(arm[:2] @ to_robot) / flat))
                                        ) < _TOWARDS
    if towards and raised and hand[2] > head[2] - 0.3:
        return "stop"
    lifted = flat > 0.5 * reach  # the arm is held out, not hanging (over 30° from down)
    if reach >= _STRETCHED and lifted and not (towards and raised):
        return "pointing"
    if not lifted and hand[2] > head[2] + _ABOVE_HEAD:
        return "raising"
    return "none"


def person_gesture(frames: np.ndarray, robot: tuple[float, float]) -> str:
    """What the person does, in the words the world's people are described with:
    ``waving``, ``raising_left_arm``/``raising_right_arm``, ``pointing_left``/
    ``pointing_right``, ``stop`` or ``none``. Left and right are the person's own: they
    face the robot, so their right hand is on the robot's left."""
    gesture = classify_gesture(frames, robot)
    if gesture not in ("raising", "pointing"):
        return gesture
    frames = np.asarray(frames, dtype=float)
    head, shoulder, hand = (frames[:, index].mean(axis=0) for index in (0, 1, 3))
    facing = np.array([robot[0] - head[0], robot[1] - head[1]])
    their_right = np.array([facing[1], -facing[0]])
    if gesture == "raising":
        side = "right" if float((shoulder - head)[:2] @ their_right) > 0 else "left"
        return f"raising_{side}_arm"
    side = "right" if float((hand - head)[:2] @ their_right) > 0 else "left"
    return f"pointing_{side}"


def gesture_from_depth(frames: Sequence[RgbdFrame], poses: Sequence[Pose],
                       person: tuple[float, float]) -> str:
    """What the person near ``person`` (map frame, as the leg tracker places them) does in a
    burst of head-camera ``frames`` (about a second at 10 Hz), each taken from the robot's
    pose of the same index in ``poses``: ``person_gesture``'s names ("stop",
    "pointing_left", "waving", ...), "none" when the frames show no one there."""
    track = arm_track(frames, poses, person)
    if track is None:
        return "none"
    return person_gesture(track, (poses[-1].x, poses[-1].y))


def pointing_ray(frames: np.ndarray) -> Ray:
    """The pointing ray of a window of frames: from the head through the hand (means)."""
    frames = np.asarray(frames, dtype=float)
    head, hand = frames[:, 0].mean(axis=0), frames[:, 3].mean(axis=0)
    return Ray((float(head[0]), float(head[1]), float(head[2])),
               (float(hand[0]), float(hand[1]), float(hand[2])))


def pointed_target(gesture: Ray, surfaces: Mapping[str, Surface],
                   margin: float = 0.25) -> str | None:
    """The placement whose top the ray meets first (its footprint grown by ``margin``
    metres, for aim); if it meets none, the one whose top's centre lies at the smallest
    angle from the ray, within 12°; None when nothing is near."""
    hits = []
    for name, surface in surfaces.items():
        met = gesture.meets_height(surface.height)
        if met is None:
            continue
        x, y, along = met
        if abs(x - surface.center[0]) <= surface.size[0] / 2 + margin and \
                abs(y - surface.center[1]) <= surface.size[1] / 2 + margin:
            # rank by how deep inside the grown footprint, then by distance along the ray
            inside = max(abs(x - surface.center[0]) - surface.size[0] / 2,
                         abs(y - surface.center[1]) - surface.size[1] / 2)
            hits.append((inside > 0, along, name))
    if hits:
        return min(hits)[2]
    points = {name: (s.center[0], s.center[1], s.height) for name, s in surfaces.items()}
    return pointed_object(gesture, points, math.radians(12.0))


def pointed_object(gesture: Ray, objects: Mapping[str, Point3],
                   within: float = math.radians(8.0)) -> str | None:
    """The object (name → map point) at the smallest angle from the pointing ray, if it
    is within ``within`` radians: "that one"."""
    return nearest_by_angle(gesture, objects, within)
