"""The robot's arm at a placement: pick a detected object, place it on a free spot, drop it
into a bin, all through the Body port and planned in the robot's own scene.

The scene is built from what the robot knows: the world file's furniture (footprints and
surface heights) and the objects' catalogue shapes where they stand. Where perception
gives a detection's position and heading (a box's heading from the top face of its
points) that is used; the positions of the other objects come from ``locate``, which the
wiring layer supplies: the embodied robot's ``SeenObjects`` (``homebot.embodied.hands``),
where its camera last saw each object. An object it has not seen is not in the scene.

A pick that left the hand empty is remembered: the next pick of that object chooses none
of the grasps that failed on it (aimed where it is seen now), and after
``GRASPS_TRIED`` empty hands on one object, or with no other grasp left, the arm does not
try again (``PickOutcome.TRIED_ALL``). A pick that holds it forgets its failures.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from homebot.geometry import Pose, yaw_rotation
from homebot.manipulation.grasps import IK_SEEDS, GraspCandidate, ObjectGeometry
from homebot.manipulation.ik import solve_ik
from homebot.manipulation.pick import (
    GRIP_FORCE,
    TUCKED,
    PickOutcome,
    PickPlan,
    PickResult,
    carry_pose,
    current_configuration,
    execute_pick,
    follow,
    plan_motion,
    plan_pick,
)
from homebot.manipulation.scene import Obstacle, PlanningScene
from homebot.robot import Body
from homebot.world import World, catalogue_entry, surface_height

__all__ = ["GRASPS_TRIED", "ArmControl", "Locate", "PlaceOutcome", "free_spots"]

#: where an object stands: (x, y, heading, surface height), or None when not on a surface
Locate = Callable[[str], tuple[float, float, float, float] | None]

_SCENE_REACH = 1.4  #: metres: furniture this close to the robot is in its scene
_SPOT_STEP = 0.05  #: metres between candidate spots on a surface
_SPOT_GAP = 0.03  #: metres kept between a placed object and its neighbours
_PLACE_ABOVE = 0.08  #: metres above the spot where the hand stops before lowering
_DROP_ABOVE = 0.2  #: metres above a bin's opening where the hand lets go
_REACH = 0.9  #: metres from the base's centre the arm can put things
_NEAREST = 0.55  #: metres: nearer than this the arm is too cramped to put things down
_BEST_REACH = 0.72  #: metres: spots about this far in front of the robot are tried first
_SPOTS_TRIED = 25  #: spots within reach tried before the robot says it finds none
_LET_FALL = (0.0, 0.03)  #: metres above its resting height an object may be let go
#: torso, then the arm held out in front at chest height, fingers level: offering the hand
_OFFER = np.array([0.2, 0.0, 0.5, 0.0, -1.2, 0.0, 0.7, 0.0])
_OPEN = 0.2  #: a gripper command wider than the fingers open: fully open
_CLOSING = 1.0  #: seconds the fingers get to close on what a person put in the hand
_UNKNOWN_EXTENT = (0.08, 0.08, 0.12)  #: metres: what the robot assumes an unnamed thing is
#: picks of one object that left the hand empty before the arm stops trying it
GRASPS_TRIED = 4


@dataclass(frozen=True)
class PlaceOutcome:
    """How a place (or drop) ended: done, and where the hand let go."""

    done: bool
    detail: str
    spot: tuple[float, float] | None = None
    planning_seconds: float = 0.0

    def __bool__(self) -> bool:
        return self.done


@dataclass
class _Holding:
    name: str
    grasp_height: float  #: the grasp site's height above the object's bottom
    rotation: np.ndarray
    radius: float


def free_spots(center: tuple[float, float], size: tuple[float, float],
               others: list[tuple[float, float, float]], radius: float,
               towards: tuple[float, float]) -> list[tuple[float, float]]:
    """Points of a surface (centre, size) where an object of ``radius`` fits between
    ``others`` (x, y, radius), nearest ``towards`` first."""
    half_x, half_y = size[0] / 2 - radius - 0.02, size[1] / 2 - radius - 0.02
    if half_x < 0 or half_y < 0:
        return []
    xs = np.arange(-half_x, half_x + 1e-9, _SPOT_STEP) + center[0]
    ys = np.arange(-half_y, half_y + 1e-9, _SPOT_STEP) + center[1]
    spots = [(float(x), float(y)) for x in xs for y in ys
             if all(math.dist((x, y), o[:2]) >= radius + o[2] + _SPOT_GAP for o in others)]
    spots.sort(key=lambda p: math.dist(p, towards))
    return spots


class ArmControl:
    """Picking and placing for a robot with one arm.

    Args:
        body: the drivers (arm, gripper, wrist sensor, ticks).
        world: the furniture and the catalogue.
        locate: where objects stand (see the module's docstring).
        seed: seeds the planners.
    """

    def __init__(self, body: Body, world: World, locate: Locate, seed: int = 0) -> None:
        self.body = body
        self.world = world
        self.locate = locate
        self.rng = np.random.default_rng([seed, 18])
        self.holding: _Holding | None = None
        self.last: PickResult | PlaceOutcome | None = None
        #: the grasps that left the hand empty, by object, since it was last held
        self.failed_grasps: dict[str, list[GraspCandidate]] = {}

    # ------------------------------------------------------------ the scene

    def _scene(self, base: Pose, leave_out: str | None = None) -> PlanningScene:
        here = (base.x, base.y)
        obstacles = []
        for name, placement in self.world.placements.items():
            height = surface_height(placement.model)
            cx, cy = placement.model.center
            w, d = placement.model.size
            if height <= 0 or math.dist(here, (cx, cy)) - math.hypot(w, d) / 2 > _SCENE_REACH:
                continue
            obstacles.append(Obstacle(f"surface:{name}", "box", (w, d, height),
                                      (cx, cy, height / 2)))
        for name in self.world.objects:
            if name == leave_out or (self.holding and name == self.holding.name):
                continue
            where = self.locate(name)
            if where is None or math.dist(here, where[:2]) > _SCENE_REACH:
                continue
            entry = catalogue_entry(self.world, name)
            extent = entry.extent
            obstacles.append(Obstacle(name, entry.shape.value, extent,
                                      (where[0], where[1], where[3] + extent[2] / 2), where[2]))
        return PlanningScene(self.body.arm().description(), (base.x, base.y, base.theta),
                             obstacles)

    # ------------------------------------------------------------ picking

    def pick(self, name: str, base: Pose, seen_at: tuple[float, float] | None = None,
             mass: float | None = None) -> PickResult:
        """Pick the object ``name`` (seen at ``seen_at`` if perception says) from ``base``."""
        if self.holding is not None or self.gripper_holds():
            self.last = PickResult(PickOutcome.NOT_HELD, detail="the gripper is not empty")
            return self.last
        if name not in self.world.objects:
            self.last = PickResult(PickOutcome.UNREACHABLE,
                                   detail=f"no catalogue entry for '{name}': its shape is unknown")
            return self.last
        where = self.locate(name)
        if where is None and seen_at is None:
            self.last = PickResult(PickOutcome.UNREACHABLE, detail=f"{name} is nowhere known")
            return self.last
        failed = self.failed_grasps.get(name, [])
        if self.tried_out(name):
            self.last = PickResult(PickOutcome.TRIED_ALL,
                                   detail=f"{len(failed)} grasps of {name} left the hand empty")
            return self.last
        entry = catalogue_entry(self.world, name)
        x, y = seen_at if seen_at is not None else (where[0], where[1])  # type: ignore[index]
        yaw = where[2] if where is not None else 0.0
        height = where[3] if where is not None else 0.75
        geometry = ObjectGeometry.from_shape(name, entry.shape.value, entry.extent, (x, y),
                                             yaw, height)
        scene = self._scene(base)
        plan = plan_pick(scene, geometry, current_configuration(self.body), self.rng,
                         mass=mass if mass is not None else entry.mass,
                         payload=self.body.arm().payload, avoid=failed)
        if not isinstance(plan, PickPlan):
            if plan.outcome is PickOutcome.UNREACHABLE and failed:
                plan = PickResult(PickOutcome.TRIED_ALL, detail=f"every grasp of {name} found "
                                  f"from here is like one that failed",
                                  planning_seconds=plan.planning_seconds)
            self.last = plan
            return plan
        result = execute_pick(self.body, plan, mass=entry.mass)
        if result:
            at = plan.grasp.candidate.position
            self.holding = _Holding(name, float(at[2] - height), plan.grasp.candidate.rotation,
                                    math.hypot(entry.extent[0], entry.extent[1]) / 2)
            self.failed_grasps.pop(name, None)
        else:
            self.failed_grasps.setdefault(name, []).append(plan.grasp.candidate)
            self.body.gripper().command(0.2)
            self._tuck(scene)
        self.last = result
        return result

    def tried_out(self, name: str) -> bool:
        """Whether the arm has given up on ``name``: ``GRASPS_TRIED`` picks of it left the
        hand empty (since it was last held)."""
        return len(self.failed_grasps.get(name, ())) >= GRASPS_TRIED

    # ------------------------------------------------------------ taking from a person

    def offer_hand(self, base: Pose) -> None:
        """Hold the open hand out in front, fingers level (Cosero §7.3.1), for a person to
        put something in."""
        scene = self._scene(base)
        here = current_configuration(self.body)
        self.body.gripper().command(_OPEN)
        path = plan_motion(scene, here, _OFFER, self.rng, gripper=_OPEN)
        follow(self.body, path or [here, _OFFER])

    def hold_out(self, base: Pose) -> None:
        """Hold what the hand holds out in front, at the offering pose, for a person to
        take (Cosero §7.3.1)."""
        scene = self._scene(base)
        here = current_configuration(self.body)
        path = plan_motion(scene, here, _OFFER, self.rng, gripper=0.2,
                           allowed=scene.without(scene.obstacles))
        follow(self.body, path or [here, _OFFER])

    def let_go(self) -> None:
        """Open the fingers on what the hand holds: someone has taken it."""
        self.body.gripper().command(_OPEN)
        self.body.tick(max(1, round(_CLOSING / self.body.tick_period)))
        self.holding = None

    def tuck(self, base: Pose) -> None:
        """Bring the arm back in (with whatever it holds)."""
        self._tuck(self._scene(base))

    def close_on_handed(self, name: str, base: Pose) -> bool:
        """Close the offered hand on ``name``, which a person put in it (a name the world's
        catalogue does not know: something of a cup's size): whether the fingers then hold
        something (sensed: they stand apart). If they do, the arm draws it in to carry it."""
        if self.holding is not None:
            return False
        self.body.gripper().command(0.0, GRIP_FORCE)
        self.body.tick(max(1, round(_CLOSING / self.body.tick_period)))
        known = name in self.world.objects
        extent = catalogue_entry(self.world, name).extent if known else _UNKNOWN_EXTENT
        scene = self._scene(base, leave_out=name if known else None)
        _, rotation = scene.grasp_frame(current_configuration(self.body))
        # Held out to the robot, it sits centred between the fingertips.
        self.holding = _Holding(name, extent[2] / 2, rotation,
                                math.hypot(extent[0], extent[1]) / 2)
        if not self.gripper_holds():
            self.holding = None
            self.body.gripper().command(_OPEN)
            return False
        # Drawn in as a picked object is carried, fingers as they took it: swung down to
        # the tucked pose, a round thing squeezes out between the pads.
        here = current_configuration(self.body)
        carry = carry_pose(scene, here, rotation)
        path = plan_motion(scene, here, carry, self.rng, gripper=0.2,
                           allowed=scene.without(scene.obstacles))
        follow(self.body, path or [here, carry])
        return True

    def hand_orientation(self, base: Pose) -> np.ndarray:
        """The hand's orientation on the map (3 × 3), from the joints' positions: the
        wrist sensor's frame turned onto the map."""
        _, rotation = self._scene(base).grasp_frame(current_configuration(self.body))
        return rotation

    def gripper_holds(self) -> bool:
        """Sensed: the fingers stand apart though told to close (something is between)."""
        state = self.body.gripper().state()
        return self.holding is not None and state.width > 0.006

    def _tuck(self, scene: PlanningScene) -> None:
        here = current_configuration(self.body)
        path = plan_motion(scene, here, TUCKED, self.rng, gripper=0.2,
                           allowed=scene.without(scene.obstacles))
        follow(self.body, path or [here, TUCKED])

    # ------------------------------------------------------------ placing and dropping

    def place(self, placement: str, base: Pose, *, drop: bool = False) -> PlaceOutcome:
        """Put what the hand holds on a free spot of ``placement`` (or let it fall into it
        from above when ``drop``, as into a bin); then open and tuck the arm."""
        started = time.process_time()
        holding = self.holding
        if holding is None:
            self.last = PlaceOutcome(False, "the hand holds nothing")
            return self.last
        model = self.world.placements[placement].model
        height = surface_height(model)
        scene = self._scene(base)
        others = []
        for name, obstacle in scene.obstacles.items():
            if obstacle.shape != "box" or not name.startswith("surface:"):
                others.append((obstacle.center[0], obstacle.center[1],
                               math.hypot(*obstacle.extents[:2]) / 2))
        front = (base.x + _BEST_REACH * math.cos(base.theta),
                 base.y + _BEST_REACH * math.sin(base.theta))
        spots = [(float(model.center[0]), float(model.center[1]))] if drop else free_spots(
            model.center, model.size, others, holding.radius, front)
        above = _DROP_ABOVE if drop else _PLACE_ABOVE
        current = current_configuration(self.body)
        within_reach = [spot for spot in spots
                        if _NEAREST <= math.dist(spot, (base.x, base.y)) <= _REACH]
        for spot in within_reach[:_SPOTS_TRIED]:
            rotation = _turned(holding.rotation, base, spot)
            release = np.array([*spot, height + holding.grasp_height + 0.005])
            high = release + np.array([0.0, 0.0, above])
            found = _release_configurations(scene, release, high, rotation, current)
            if found is None:
                continue
            over, down = found
            path = plan_motion(scene, current, over, self.rng, gripper=0.1)
            if path is None:
                continue
            seconds = time.process_time() - started
            follow(self.body, path)
            if not drop:
                follow(self.body, [over, down], settle=0.3)
            self.body.gripper().command(0.2)
            self.body.tick(max(1, round(0.5 / self.body.tick_period)))
            self.holding = None
            follow(self.body, [down, over], settle=0.1)
            self._tuck(scene)
            self.last = PlaceOutcome(True, "dropped" if drop else "placed", spot, seconds)
            return self.last
        self.last = PlaceOutcome(False, f"no free spot on {placement} within reach",
                                 planning_seconds=time.process_time() - started)
        return self.last


def _release_configurations(scene: PlanningScene, release: np.ndarray, high: np.ndarray,
                            rotation: np.ndarray, current: np.ndarray
                            ) -> tuple[np.ndarray, np.ndarray] | None:
    """Collision-free configurations with the hand at ``release`` and above it at ``high``.

    The torso is first left to the solver; then held at its top, where the shoulder stands
    well above a high surface and a hand held level reaches over it without the elbow
    dipping into it. A flat thing held from the side is let fall the last centimetres:
    lowered to the surface, the fingers below it would meet the surface first."""
    for raised, torso, seed in itertools.product(_LET_FALL, (None, float(scene.upper[0])),
                                                 (current, *IK_SEEDS)):
        posture = seed.copy()
        posture[0] = scene.upper[0] - 0.15 if torso is None else torso
        down = solve_ik(scene, release + np.array([0.0, 0.0, raised]), rotation, [seed],
                        posture=posture, torso=torso)
        if down is None or scene.collides(down, gripper=0.2):
            continue
        over = solve_ik(scene, high, rotation, [down], torso=torso)
        if over is None or scene.collides(over, gripper=0.2):
            continue
        return over, down
    return None


def _turned(rotation: np.ndarray, base: Pose, spot: tuple[float, float]) -> np.ndarray:
    """The grasp's orientation turned about the vertical so that it faces ``spot`` from the
    base as it faced the object when picked (a side grasp approaches from the robot)."""
    approach = rotation[:, 0]
    horizontal = math.hypot(approach[0], approach[1])
    if horizontal < 0.3:  # a top grasp: keep it as it was
        return rotation
    now = math.atan2(approach[1], approach[0])
    want = math.atan2(spot[1] - base.y, spot[0] - base.x)
    turn = want - now
    turned: np.ndarray = yaw_rotation(turn) @ rotation
    return turned
