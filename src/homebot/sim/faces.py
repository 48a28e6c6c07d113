"""Grey face images of people: a parametric face per identity, seen with varying pose and light.

Each identity has its own geometry and texture (face oval, skin and hair
brightness, hair line, eye spacing, size and darkness, brows, nose length, mouth
width and position), drawn from its name and a seed. A view of it adds a head
turn (features shift and the oval narrows), a roll, a light level and a side
light, and sensor noise, and sets the face at a seeded place and size in a
cluttered grey image, as a head camera's crop around a person's head gives it.
Everything is deterministic by seed.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from homebot.geometry import wrap_angle

if TYPE_CHECKING:
    from homebot.sim.body import SimBody

__all__ = ["FaceCamera", "FaceIdentity", "background_patch", "face_identity", "face_view"]

IMAGE = 80  #: pixels: the side of a view
FACE_SIZE = (30, 46)  #: pixels: a face's side in a view


@dataclass(frozen=True, slots=True)
class FaceIdentity:
    """What makes one face this person's: proportions and brightnesses in [0, 1] units."""

    name: str
    oval: tuple[float, float]  #: half width, half height of the face, of the window
    skin: float
    hair: float
    hairline: float  #: height of the hair's edge above the eyes
    eye_gap: float
    eye_size: float
    eye_dark: float
    eye_height: float
    brow: float  #: thickness
    nose: float  #: length
    mouth_width: float
    mouth_height: float
    mouth_dark: float


def face_identity(name: str, seed: int = 0) -> FaceIdentity:
    """The face of ``name`` (the same name and seed, the same face)."""
    rng = np.random.default_rng([seed, zlib.crc32(name.encode())])
    u = rng.uniform
    return FaceIdentity(
        name, (u(0.30, 0.40), u(0.40, 0.48)), u(0.45, 0.85), u(0.05, 0.45), u(0.12, 0.30),
        u(0.15, 0.25), u(0.035, 0.065), u(0.0, 0.25), u(-0.12, -0.02), u(0.015, 0.05),
        u(0.10, 0.22), u(0.10, 0.22), u(0.18, 0.30), u(0.15, 0.45))


def _render_face(identity: FaceIdentity, size: int, yaw: float, roll: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The face alone, ``size`` pixels square: brightness and a mask of where it is."""
    f = identity
    coords = (np.arange(size) + 0.5) / size - 0.5
    x, y = np.meshgrid(coords, -coords)  # y up
    cos, sin = math.cos(roll), math.sin(roll)
    x, y = cos * x + sin * y, -sin * x + cos * y
    shift = 0.35 * math.sin(yaw) * f.oval[0]  # features move with the head's turn
    squeeze = math.cos(yaw)
    inside = (x / (f.oval[0] * (0.75 + 0.25 * squeeze))) ** 2 + (y / f.oval[1]) ** 2 <= 1.0
    image = np.full((size, size), f.skin)
    image[inside & (y > f.hairline)] = f.hair
    fx = (x - shift) / max(squeeze, 0.3)
    for side in (-1, 1):
        eye = ((fx - side * f.eye_gap) / (1.4 * f.eye_size)) ** 2 + \
            ((y - f.eye_height) / f.eye_size) ** 2 <= 1.0
        image[eye] = f.eye_dark
        brow = (np.abs(fx - side * f.eye_gap) < 1.6 * f.eye_size) & \
            (np.abs(y - f.eye_height - 2.2 * f.eye_size) < f.brow)
        image[brow] = 0.6 * f.hair + 0.2 * f.skin
    nose = (np.abs(fx) < 0.035) & (y < f.eye_height) & (y > f.eye_height - f.nose)
    image[nose] = 0.8 * f.skin
    mouth = (np.abs(fx) < f.mouth_width) & (np.abs(y + f.mouth_height) < 0.025)
    image[mouth] = f.mouth_dark
    return image, inside


def background_patch(rng: np.random.Generator, size: int = IMAGE) -> np.ndarray:
    """Grey clutter: smooth shading, a few rectangles and stripes, and noise (no face)."""
    image = np.full((size, size), rng.uniform(0.2, 0.8))
    yy, xx = np.mgrid[0:size, 0:size] / size
    image += rng.uniform(-0.2, 0.2) * xx + rng.uniform(-0.2, 0.2) * yy
    for _ in range(int(rng.integers(2, 7))):
        x0, y0 = rng.integers(0, size, 2)
        w, h = rng.integers(4, size // 2, 2)
        image[y0:y0 + h, x0:x0 + w] = rng.uniform(0.0, 1.0)
    if rng.random() < 0.5:
        image[:, :: int(rng.integers(3, 9))] *= rng.uniform(0.6, 1.0)
    image += rng.normal(0.0, 0.03, image.shape)
    patch: np.ndarray = np.clip(image * 255, 0, 255).astype(np.uint8)
    return patch


def face_view(identity: FaceIdentity, rng: np.random.Generator, *, yaw: float = 0.35,
              roll: float = 0.12, light: float = 0.3, noise: float = 0.04
              ) -> tuple[np.ndarray, tuple[int, int, int]]:
    """One grey view (``IMAGE`` square, uint8) of ``identity`` and where the face is
    (x, y, side in pixels); pose within ±``yaw``/±``roll`` radians, light level within
    ±``light`` and a side light, Gaussian ``noise``."""
    image = background_patch(rng).astype(float) / 255
    size = int(rng.integers(FACE_SIZE[0], FACE_SIZE[1] + 1))
    face, inside = _render_face(identity, size, rng.uniform(-yaw, yaw), rng.uniform(-roll, roll))
    x, y = (int(v) for v in rng.integers(0, IMAGE - size + 1, 2))
    patch = image[y:y + size, x:x + size]
    patch[inside] = face[inside]
    gain = 1.0 + rng.uniform(-light, light)
    side_light = rng.uniform(-light, light) * (np.arange(IMAGE) / IMAGE - 0.5)
    image = image * gain + side_light[None, :] + rng.normal(0.0, noise, image.shape)
    return np.clip(image * 255, 0, 255).astype(np.uint8), (x, y, size)


class FaceCamera:
    """The head camera's close-ups of the face of the person in front of a ``SimBody``.

    The person nearest the camera's axis, within ``reach`` metres and ``half_angle``
    radians of where the head points, is the one seen; each call renders ``views`` grey
    views of their face (``face_view``: pose, light and noise vary), as a head camera's
    crops of a person facing it give them over a second or two. Their face is
    ``face_identity(name, face_seed)``: the same person, the same face, whatever the
    run. Deterministic by the simulation's seed and the body's clock.
    """

    def __init__(self, body: SimBody, *, reach: float = 2.5, half_angle: float = 0.5,
                 face_seed: int = 0) -> None:
        self.body = body
        self.reach = reach
        self.half_angle = half_angle
        self.face_seed = face_seed
        self._looks = 0  #: each look renders new views, even at the same moment

    def facing(self) -> str | None:
        """Who stands in front of the camera (the truth: for rendering only)."""
        pose = self.body.true_pose()
        axis = pose.theta + self.body.head().pan
        best, best_angle = None, math.inf
        for name, state in sorted(self.body.sim.people.items()):
            dx, dy = state.position[0] - pose.x, state.position[1] - pose.y
            angle = abs(wrap_angle(math.atan2(dy, dx) - axis))
            if math.hypot(dx, dy) <= self.reach and angle <= self.half_angle and \
                    angle < best_angle:
                best, best_angle = name, angle
        return best

    def __call__(self, views: int = 6) -> list[np.ndarray]:
        """``views`` face images of the person in front; none when nobody is."""
        name = self.facing()
        if name is None:
            return []
        identity = face_identity(name, self.face_seed)
        self._looks += 1
        rng = np.random.default_rng([self.body.sim.seed, zlib.crc32(name.encode()),
                                     round(self.body.now() * 1000), self._looks])
        return [face_view(identity, rng)[0] for _ in range(views)]
