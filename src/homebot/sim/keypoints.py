"""How a person moves their arm in a gesture, and its keypoints as a skeleton tracker gives them.

Each frame holds four points in the map frame (metres, z up): head, shoulder,
elbow and hand of the gesturing arm (Cosero §7.1.3 finds the same four). The
person stands at a place facing the robot and points at a target (the eye-hand
line aims at it, with a few degrees of aiming error), waves (the raised hand
swings from side to side), shows stop (a raised open hand held out towards the
robot), raises the arm straight up, or stands with the arm hanging; or draws a
dynamic gesture with the hand in front of them (``DYNAMIC_MOTIONS``): circles,
swipes to their left or right (then drops the arm and starts again), or beckons
(the forearm brought up towards the face and down, again and again). To point at
something behind them, they turn their trunk until it is no more than 100° from
the robot's direction.

``ArmMotion`` is one person's way of making a gesture (which arm, how they aim,
how fast they wave) and ``ArmMotion.at`` the arm's posture at given moments: the
simulator draws people's arms in the head camera's image from it
(``body_tracker.person_arms``). ``gesture_keypoints`` draws a motion and samples it
with Gaussian noise on every point, as a skeleton tracker's output. Deterministic by seed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["DYNAMIC_MOTIONS", "GESTURES", "ArmMotion", "draw_motion", "gesture_keypoints"]

GESTURES = ("pointing", "waving", "stop", "raising", "none")
#: motions drawn in the hand's path (``perception.strokes``); waving is ``waving``
DYNAMIC_MOTIONS = ("circle", "swipe_left", "swipe_right", "beckon")
_SWIPE = (0.35, 0.5)  #: shares of a swipe's period: the swipe ends, then the arm drops
_SWIPE_SPAN = (-0.25, 0.45)  #: metres along the person's right the swiping hand goes between
_HEIGHT = 1.75  #: metres: the person the proportions below are for
_HEAD = 1.62  #: metres
_SHOULDER = (0.19, 1.42)  #: sideways from the head's axis, height
_UPPER, _FORE = 0.30, 0.32  #: arm segment lengths, metres
#: radians: the farthest from the robot a person points without turning their trunk
_POINT_ASIDE = math.radians(100.0)


@dataclass(frozen=True)
class ArmMotion:
    """One person's way of making ``gesture`` with their ``side`` arm.

    Attributes:
        gesture: one of ``GESTURES``.
        side: the person's ``left`` or ``right`` arm.
        height: the person's height, metres (places head and shoulders).
        target: where a pointing gesture aims (map frame).
        aim_error: the offset added to the unit pointing direction (their aiming error).
        beat: waves (circles, swipes, beckons) a second.
        phase: radians: where in a wave they are at time 0.
        size: metres: a circle's radius; its sign, the way round (positive: anticlockwise
            as the robot sees it).
    """

    gesture: str
    side: str
    height: float = _HEIGHT
    target: tuple[float, float, float] | None = None
    aim_error: tuple[float, float, float] = (0.0, 0.0, 0.0)
    beat: float = 2.0
    phase: float = 0.0
    size: float = 0.15

    def at(self, person: tuple[float, float], robot: tuple[float, float],
           times: np.ndarray) -> np.ndarray:
        """Keypoints (len(times), 4, 3) of the person standing at ``person`` facing the
        robot at ``robot``: head, shoulder, elbow, hand, at ``times`` (seconds)."""
        facing = math.atan2(robot[1] - person[1], robot[0] - person[0])
        if self.gesture == "pointing" and self.target is not None:
            # pointing behind them, people turn their trunk towards the target
            aside = math.atan2(self.target[1] - person[1], self.target[0] - person[0]) - facing
            aside = math.atan2(math.sin(aside), math.cos(aside))
            if abs(aside) > _POINT_ASIDE:
                facing += aside - math.copysign(_POINT_ASIDE, aside)
        forward = np.array([math.cos(facing), math.sin(facing), 0.0])
        right = np.array([math.sin(facing), -math.cos(facing), 0.0])
        # facing the robot, the person's right hand is on the robot's left ("right" vector)
        side_sign = 1.0 if self.side == "right" else -1.0
        scale = self.height / _HEIGHT
        head = np.array([person[0], person[1], _HEAD * scale])
        shoulder = head + side_sign * _SHOULDER[0] * right
        shoulder[2] = _SHOULDER[1] * scale
        frames = len(times)
        hands = np.empty((frames, 3))
        elbows = np.empty((frames, 3))
        if self.gesture == "pointing":
            if self.target is None:
                raise ValueError("a pointing gesture needs a target")
            ray = np.asarray(self.target, dtype=float) - head
            ray /= np.linalg.norm(ray)
            turned = ray + np.asarray(self.aim_error)
            ray = turned / np.linalg.norm(turned)
            # the hand on the eye-target line, an arm's length from the shoulder
            hand = _on_ray(head, ray, shoulder, _UPPER + _FORE - 0.02)
            hands[:] = hand
            elbows[:] = shoulder + (hand - shoulder) * 0.48 - np.array([0, 0, 0.03])
        elif self.gesture == "stop":
            hand = shoulder + 0.45 * forward + np.array([0.0, 0.0, 0.25])
            hands[:] = hand
            elbows[:] = shoulder + 0.22 * forward + np.array([0.0, 0.0, 0.05])
        elif self.gesture == "raising":
            elbows[:] = shoulder + np.array([0.0, 0.0, _UPPER]) + 0.04 * side_sign * right
            hands[:] = elbows + np.array([0.0, 0.0, _FORE]) + 0.02 * forward
        elif self.gesture == "waving":
            swing = 0.15 * np.sin(2 * math.pi * self.beat * times + self.phase)
            elbow = shoulder + 0.12 * forward + side_sign * 0.18 * right - np.array(
                [0.0, 0.0, 0.12])
            elbows[:] = elbow
            hands[:] = elbow + np.array([0.0, 0.0, 0.28]) + swing[:, None] * right[None, :]
        elif self.gesture in DYNAMIC_MOTIONS:
            self._dynamic(times, shoulder, forward, right, side_sign, elbows, hands)
        else:
            elbows[:] = shoulder - np.array([0.0, 0.0, _UPPER]) + 0.03 * forward
            hands[:] = elbows - np.array([0.0, 0.0, _FORE]) + 0.06 * forward
        heads = np.repeat(head[None, :], frames, axis=0)
        shoulders = np.repeat(shoulder[None, :], frames, axis=0)
        return np.stack((heads, shoulders, elbows, hands), axis=1)


    def _dynamic(self, times: np.ndarray, shoulder: np.ndarray, forward: np.ndarray,
                 right: np.ndarray, side_sign: float, elbows: np.ndarray,
                 hands: np.ndarray) -> None:
        """Elbows and hands (filled in) of a circle, a swipe or beckoning."""
        up = np.array([0.0, 0.0, 1.0])
        turn = 2 * math.pi * self.beat * times + self.phase
        if self.gesture == "circle":
            centre = shoulder + 0.35 * forward + 0.1 * side_sign * right + 0.05 * up
            way = math.copysign(1.0, self.size)
            # anticlockwise as the robot sees it is clockwise in the person's right-up plane
            hands[:] = centre + abs(self.size) * (np.cos(-way * turn)[:, None] * right
                                                  + np.sin(-way * turn)[:, None] * up)
            elbows[:] = shoulder + 0.5 * (hands - shoulder) - 0.08 * up
        elif self.gesture == "beckon":
            elbow = shoulder + 0.22 * forward + 0.1 * side_sign * right - 0.12 * up
            lift = math.radians(55.0) + math.radians(35.0) * np.sin(turn)  # from level
            elbows[:] = elbow
            hands[:] = elbow + _FORE * (np.cos(lift)[:, None] * forward
                                        + np.sin(lift)[:, None] * up)
        else:  # a swipe, then the arm drops and comes back up at the start
            share = np.mod(turn / (2 * math.pi), 1.0)
            along = np.clip(share / _SWIPE[0], 0.0, 1.0)
            along = along * along * (3 - 2 * along)  # smooth start and stop
            start, end = _SWIPE_SPAN if self.gesture == "swipe_right" else _SWIPE_SPAN[::-1]
            held = shoulder + 0.4 * forward + 0.05 * up + (
                start + (end - start) * along)[:, None] * right
            down = share >= _SWIPE[1]
            hanging_elbow = shoulder - _UPPER * up + 0.03 * forward
            hands[:] = np.where(down[:, None], hanging_elbow - _FORE * up + 0.06 * forward,
                                held)
            elbows[:] = np.where(down[:, None], hanging_elbow,
                                 shoulder + 0.5 * (held - shoulder) - 0.1 * up)


def draw_motion(gesture: str, rng: np.random.Generator, *,
                target: tuple[float, float, float] | None = None, aim: float = 0.03,
                side: str | None = None, height: float = _HEIGHT) -> ArmMotion:
    """A person's way of making ``gesture``, drawn from ``rng``: the arm (``side`` None:
    either), the aiming error (standard deviation ``aim``, radians) and the waving beat."""
    if gesture not in GESTURES + DYNAMIC_MOTIONS:
        raise ValueError(f"unknown gesture {gesture!r}; one of "
                         f"{', '.join(GESTURES + DYNAMIC_MOTIONS)}")
    chosen = side if side is not None else ("right" if rng.random() < 0.5 else "left")
    if chosen not in ("left", "right"):
        raise ValueError(f"unknown side {side!r}; left or right")
    aim_error = (0.0, 0.0, 0.0)
    beat, phase, size = 2.0, 0.0, 0.15
    if gesture == "pointing":
        if target is None:
            raise ValueError("a pointing gesture needs a target")
        error = rng.normal(0.0, aim, 3)
        aim_error = (float(error[0]), float(error[1]), float(error[2]))
    elif gesture == "waving":
        beat = float(rng.uniform(1.5, 2.5))  # waves a second
        phase = float(rng.uniform(0, 2 * math.pi))
    elif gesture in DYNAMIC_MOTIONS:
        beat = float(rng.uniform(*_DYNAMIC_BEATS[gesture]))
        phase = float(rng.uniform(0, 2 * math.pi))
        size = float(rng.uniform(0.12, 0.2)) * (1.0 if rng.random() < 0.5 else -1.0)
    return ArmMotion(gesture, chosen, height, target, aim_error, beat, phase, size)


#: each dynamic motion's beats a second (circles, swipes, beckons)
_DYNAMIC_BEATS = {"circle": (0.6, 0.9), "swipe_left": (0.5, 0.6), "swipe_right": (0.5, 0.6),
                  "beckon": (1.2, 2.0)}


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
    motion = draw_motion(gesture, rng, target=target, aim=aim, side=side, height=height)
    points = motion.at(person, robot, np.arange(round(seconds * rate)) / rate)
    noisy: np.ndarray = points + rng.normal(0.0, noise, points.shape)
    return noisy


def _on_ray(origin: np.ndarray, ray: np.ndarray, centre: np.ndarray, radius: float
            ) -> np.ndarray:
    """The point of the ray from ``origin`` at ``radius`` from ``centre`` (the far one)."""
    offset = origin - centre
    b = float(offset @ ray)
    c = float(offset @ offset) - radius ** 2
    along = -b + math.sqrt(max(b * b - c, 0.0))
    point: np.ndarray = origin + along * ray
    return point
