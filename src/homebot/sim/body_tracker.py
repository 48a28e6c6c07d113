"""People as the head camera shows them: solids in the RGB-D image, and arm keypoints.

``person_solids`` builds a person for the camera's ray caster in their true
posture: standing (legs, trunk and head one above the other), sitting (trunk on
a seat, legs forward) or lying (a long low body on the floor or on the bed under
them), the top in the colour of their upper clothes and the legs in their
trousers'. ``BodyTracker`` is the skeleton tracker a real head camera runs
(OpenNI/NITE, a ROS ``body_tracker``): turned to a person, it gives the
keypoints of the arm they gesture with (``keypoints.gesture_keypoints``), with
noise, in the robot's base frame. What people do is read from the truth only to
render it; naming it is perception's work. Deterministic by the simulation's seed
and the body's clock.
"""

from __future__ import annotations

import math
import zlib
from typing import TYPE_CHECKING

import numpy as np
from shapely.geometry import Point as ShapelyPoint

from homebot.geometry import Pose, to_frame, wrap_angle
from homebot.robot import PersonView
from homebot.sim.camera import Solid
from homebot.sim.keypoints import gesture_keypoints
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

if TYPE_CHECKING:
    from homebot.sim.body import SimBody

__all__ = ["BodyTracker", "clothes_rgb", "lying_body_outline", "person_height",
           "person_solids"]

_SPOT = 0.6  #: metres from the spot looked at within which a person is the one seen
_RANGE = 6.0  #: metres: the depth camera's reach
_HALF_VIEW = math.radians(29.0)  #: half the camera's horizontal field of view
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


class BodyTracker:
    """The skeleton tracker of a ``SimBody``'s head camera: ``PersonView`` s of the
    person standing at a spot the head is turned to.

    Args:
        body: the simulated body whose head camera looks.
    """

    def __init__(self, body: SimBody) -> None:
        self.body = body
        self._looks = 0  #: each look renders anew, even at the same moment

    def __call__(self, spot: tuple[float, float]) -> PersonView | None:
        body = self.body
        pose = body.true_pose()
        target = pose.apply(*spot)
        near = sorted((math.dist(state.position, target), name)
                      for name, state in body.sim.people.items())
        if not near or near[0][0] > _SPOT:
            return None
        name = near[0][1]
        state = body.sim.people[name]
        distance = math.dist(state.position, pose.xy())
        bearing = math.atan2(state.position[1] - pose.y, state.position[0] - pose.x)
        axis = pose.theta + body.head().pan
        if distance > _RANGE or abs(wrap_angle(bearing - axis)) > _HALF_VIEW:
            return None
        self._looks += 1
        rng = np.random.default_rng([body.sim.seed, zlib.crc32(name.encode()),
                                     round(body.now() * 1000), self._looks])
        arm = self._arm(state.model, state.position, pose, person_height(name, state.model), rng)
        return PersonView(stamp=body.now(),
                          arm=_to_base(arm.reshape(-1, 3), pose).reshape(arm.shape))

    @staticmethod
    def _arm(model: PersonModel, position: tuple[float, float], pose: Pose, height: float,
             rng: np.random.Generator) -> np.ndarray:
        gesture = model.gesture
        robot = pose.xy()
        if gesture is Gesture.WAVING:
            return gesture_keypoints("waving", position, robot, rng, height=height)
        if gesture in (Gesture.RAISING_LEFT_ARM, Gesture.RAISING_RIGHT_ARM):
            side = "left" if gesture is Gesture.RAISING_LEFT_ARM else "right"
            return gesture_keypoints("raising", position, robot, rng, side=side, height=height)
        if gesture in (Gesture.POINTING_LEFT, Gesture.POINTING_RIGHT):
            side = "left" if gesture is Gesture.POINTING_LEFT else "right"
            # facing the robot, the person's right is the robot's left
            facing = math.atan2(robot[1] - position[1], robot[0] - position[0])
            turn = -math.pi / 2 if side == "right" else math.pi / 2
            target = (position[0] + _POINTING_REACH * math.cos(facing + turn),
                      position[1] + _POINTING_REACH * math.sin(facing + turn), 0.75)
            return gesture_keypoints("pointing", position, robot, rng, target=target,
                                     side=side, height=height)
        return gesture_keypoints("none", position, robot, rng, height=height)


def _to_base(points: np.ndarray, pose: Pose) -> np.ndarray:
    """Map-frame points (n, 3) into the base frame of a robot at ``pose``."""
    return to_frame(pose, points)
