"""People as the head camera shows them: their bodies and arms as solids in the RGB-D image.

``person_solids`` builds a person for the camera's ray caster in their true
posture: standing (legs, trunk and head one above the other), sitting (trunk on
a seat, legs forward) or lying (a long low body on the floor or on the bed under
them), the top in the colour of their upper clothes and the legs in their
trousers'. ``PeopleArms`` adds their arms as they move them at the frame's moment
(``keypoints.ArmMotion``: the gesture their world entry names, or one a trial
gives them): sleeved upper arm and forearm, elbow and bare hand. What people do is
read from the truth only to draw it; reading it from the depth image is perception's
work (``homebot.perception.body_parts``). Deterministic by the simulation's seed and
the body's clock.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import replace

import numpy as np
from shapely.geometry import Point as ShapelyPoint

from homebot.sim.camera import Limb, Solid
from homebot.sim.keypoints import ArmMotion, draw_motion
from homebot.world import (
    COLOUR_PALETTE,
    LEG_GARMENTS,
    Gesture,
    PersonModel,
    PlacementKind,
    Posture,
    Shape,
    World,
    surface_height,
)

__all__ = ["PeopleArms", "arm_solids", "clothes_rgb", "lying_body_outline", "person_height",
           "person_solids"]

_ARM_RADIUS = 0.045  #: metres: a sleeved arm's
_HAND_RADIUS = 0.05  #: metres: a hand's, fingers closed
_POINTING_REACH = 2.0  #: metres to the side a pointing person points, at table height
_UNKNOWN_CLOTH = (128, 128, 128)
_LEGS_RGB = (60, 60, 75)  #: trousers of no stated colour: dark
_SKIN_RGB = (225, 185, 150)
_SEAT = 0.45  #: metres: a seated person's seat
_HEAD = 0.22  #: metres across
_TRUNK, _LEGS = 0.40, 0.30  #: metres across the trunk and the legs together
_LYING = (0.45, 0.24)  #: metres: a lying body's width and thickness


def person_height(name: str, model: PersonModel | None = None) -> float:
    """A person's height, metres: as the world file gives it, else drawn from the name
    (1.55-1.95; the same for the same name in every run: visitors have none declared)."""
    if model is not None and model.height is not None:
        return model.height
    return 1.55 + 0.4 * (zlib.crc32(f"height:{name}".encode()) % 1000) / 999


def clothes_rgb(clothes: list[str], *, bottom: bool) -> tuple[int, int, int] | None:
    """The colour of the first of ``clothes`` ("red sweater") worn on the legs (``bottom``:
    trousers, jeans, a skirt...) or above them (anything else); an item without a palette
    colour is a middle grey; None when nothing is worn there."""
    for item in clothes:
        words = item.lower().split()
        if not words or (words[-1] in LEG_GARMENTS) != bottom:
            continue
        colours = [COLOUR_PALETTE[word] for word in words if word in COLOUR_PALETTE]
        return colours[0] if colours else _UNKNOWN_CLOTH
    return None


def person_solids(world: World, name: str, model: PersonModel, posture: Posture,
                  position: tuple[float, float], heading: float) -> list[Solid]:
    """The solids the camera sees of a person in ``posture``: where ``position`` is, facing
    ``heading``."""
    height = person_height(name, model)
    top = clothes_rgb(model.clothes, bottom=False) or _UNKNOWN_CLOTH
    legs = clothes_rgb(model.clothes, bottom=True) or _LEGS_RGB
    x, y = position
    if posture is Posture.LYING:
        bed, yaw = _lying_on(world, position, heading)
        width, thick = _LYING
        return [Solid(Shape.BOX, (height - _HEAD, width, thick), top, x, y, bed, yaw),
                Solid(Shape.SPHERE, (_HEAD, _HEAD, _HEAD), _SKIN_RGB,
                      x + (height - _HEAD) / 2 * math.cos(yaw),
                      y + (height - _HEAD) / 2 * math.sin(yaw), bed)]
    if posture is Posture.SITTING:
        trunk = 0.53 * height - _HEAD
        knees = (x + 0.3 * math.cos(heading), y + 0.3 * math.sin(heading))
        return [Solid(Shape.CYLINDER, (_LEGS, _LEGS, _SEAT), legs, *knees, 0.0),
                Solid(Shape.CYLINDER, (_TRUNK, _TRUNK, trunk), top, x, y, _SEAT),
                Solid(Shape.SPHERE, (_HEAD, _HEAD, _HEAD), _SKIN_RGB, x, y, _SEAT + trunk)]
    hips = 0.48 * height
    return [Solid(Shape.CYLINDER, (_LEGS, _LEGS, hips), legs, x, y, 0.0),
            Solid(Shape.CYLINDER, (_TRUNK, _TRUNK, height - _HEAD - hips), top, x, y, hips),
            Solid(Shape.SPHERE, (_HEAD, _HEAD, _HEAD), _SKIN_RGB, x, y, height - _HEAD)]


def _lying_on(world: World, position: tuple[float, float], heading: float
              ) -> tuple[float, float]:
    """The height a person lying at ``position`` lies at (0: the floor) and the body's
    heading: along the furniture's long side, or along ``heading`` on the floor."""
    under = [p for p in world.placements.values()
             if p.model.kind is PlacementKind.FURNITURE and
             p.footprint.contains(ShapelyPoint(*position))]
    if not under:
        return 0.0, heading
    x0, y0, x1, y1 = under[0].footprint.bounds
    return max(surface_height(p.model) for p in under), 0.0 if x1 - x0 >= y1 - y0 else math.pi / 2


def lying_body_outline(world: World, name: str, model: PersonModel, posture: Posture,
                       position: tuple[float, float], heading: float
                       ) -> list[tuple[float, float]] | None:
    """What a floor-level laser sees of a person lying down, as leg-sized circles' centres
    every 10 cm along the body (a long blob, no pair of legs): nothing when they lie on
    furniture (the bed or sofa hides them); None when they are not lying."""
    if posture is not Posture.LYING:
        return None
    bed, yaw = _lying_on(world, position, heading)
    if bed > 0.0:
        return []
    length = person_height(name, model)
    # the trunk box is centred on ``position``; the head lies beyond its far end
    along = np.arange(-(length - _HEAD) / 2, (length + _HEAD) / 2 + 1e-9, 0.1)
    return [(position[0] + t * math.cos(yaw), position[1] + t * math.sin(yaw))
            for t in along]


class PeopleArms:
    """How the simulation's people move their arms, for the head camera to draw.

    Each person makes the gesture their world entry names (``PersonModel.gesture``), facing
    the robot, with the other arm hanging; how they make it (``keypoints.ArmMotion``: which
    arm waves, the aiming error, the waving beat) is drawn once per person from the seed.
    A pointing person points about 2 m to their side at table height. ``gestures`` may
    give a person another motion (a trial's, a scenario's), replacing their entry's.

    Args:
        seed: the simulation's seed.
    """

    def __init__(self, seed: int) -> None:
        self.seed = seed
        self._motions: dict[tuple[str, Gesture], ArmMotion] = {}
        #: people's motions set by a trial or scenario, instead of their world entry's
        self.gestures: dict[str, ArmMotion] = {}

    def solids(self, name: str, model: PersonModel, posture: Posture,
               position: tuple[float, float], robot: tuple[float, float], now: float
               ) -> list[Solid | Limb]:
        """Both arms of a standing or seated person at time ``now`` (none when lying)."""
        if posture is Posture.LYING:
            return []
        height = person_height(name, model)
        motion = self.gestures.get(name) or self._motion(name, model, position, robot, height)
        other = "left" if motion.side == "right" else "right"
        times = np.array([now])
        arms = [motion.at(position, robot, times)[0],
                ArmMotion("none", other, height).at(position, robot, times)[0]]
        if posture is Posture.SITTING:  # the same arms, lower by the seated head's drop
            drop = height - (_SEAT + 0.53 * height)
            arms = [arm - np.array([0.0, 0.0, drop]) for arm in arms]
        sleeve = clothes_rgb(model.clothes, bottom=False) or _UNKNOWN_CLOTH
        return [part for arm in arms for part in arm_solids(arm, sleeve)]

    def _motion(self, name: str, model: PersonModel, position: tuple[float, float],
                robot: tuple[float, float], height: float) -> ArmMotion:
        gesture = model.gesture
        key = (name, gesture)
        if key not in self._motions:
            rng = np.random.default_rng([self.seed, zlib.crc32(f"arms:{name}".encode())])
            kind, side = _GESTURE_MOTIONS[gesture]
            self._motions[key] = draw_motion(kind, rng, side=side, height=height,
                                             target=(0.0, 0.0, 0.0))
        motion = self._motions[key]
        if motion.gesture != "pointing":
            return motion
        # facing the robot, the person's right is the robot's left
        facing = math.atan2(robot[1] - position[1], robot[0] - position[0])
        turn = -math.pi / 2 if motion.side == "right" else math.pi / 2
        target = (position[0] + _POINTING_REACH * math.cos(facing + turn),
                  position[1] + _POINTING_REACH * math.sin(facing + turn), 0.75)
        return replace(motion, target=target)


#: the arm motion and arm of each gesture a world file gives a person
_GESTURE_MOTIONS: dict[Gesture, tuple[str, str | None]] = {
    Gesture.NONE: ("none", None),
    Gesture.WAVING: ("waving", None),
    Gesture.RAISING_LEFT_ARM: ("raising", "left"),
    Gesture.RAISING_RIGHT_ARM: ("raising", "right"),
    Gesture.POINTING_LEFT: ("pointing", "left"),
    Gesture.POINTING_RIGHT: ("pointing", "right"),
}


def arm_solids(keypoints: np.ndarray, sleeve: tuple[int, int, int]) -> list[Solid | Limb]:
    """An arm posed by its keypoints (head, shoulder, elbow, hand; map frame) as the
    camera draws it: the sleeved upper arm and forearm, the elbow, and the bare hand."""
    _, shoulder, elbow, hand = (tuple(float(v) for v in point) for point in keypoints)
    return [Limb((shoulder[0], shoulder[1], shoulder[2]), (elbow[0], elbow[1], elbow[2]),
                 _ARM_RADIUS, sleeve),
            Limb((elbow[0], elbow[1], elbow[2]), (hand[0], hand[1], hand[2]),
                 _ARM_RADIUS, sleeve),
            Solid(Shape.SPHERE, (2 * _ARM_RADIUS,) * 3, sleeve, elbow[0], elbow[1],
                  elbow[2] - _ARM_RADIUS),
            Solid(Shape.SPHERE, (2 * _HAND_RADIUS,) * 3, _SKIN_RGB, hand[0], hand[1],
                  hand[2] - _HAND_RADIUS)]
