"""Picking, placing and dropping through the Body port: plan, move, close, lift, sense.

Planning (``plan_pick``) selects a grasp (``select_grasp``) and plans the reach with
RRT-Connect; execution (``execute_pick``) drives the arm along the path in control ticks,
moves in, closes the gripper, lifts and retracts. Whether the object is held is sensed,
never assumed: the fingers stopped apart (something is between them) and the wrist feels
the object's weight.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Protocol

import numpy as np

from homebot.manipulation.grasps import Grasp, GraspCandidate, ObjectGeometry, select_grasp
from homebot.manipulation.ik import solve_ik
from homebot.manipulation.rrt import rrt_connect, shortcut
from homebot.manipulation.scene import PlanningScene
from homebot.robot import Arm, Gripper, JointTarget, Wrench

__all__ = [
    "GRIP_FORCE",
    "TUCKED",
    "Manipulator",
    "PickOutcome",
    "PickPlan",
    "PickResult",
    "carry_pose",
    "execute_pick",
    "plan_motion",
    "plan_pick",
]

#: the arm tucked over the base (torso, then the 7 joints): where it waits with an empty hand
TUCKED = np.array([0.2, 0.0, -1.4, 0.0, -1.8, 0.0, -1.3, 0.0])
_ESCAPE = 0.15  #: radians from a start in contact within which contact is tolerated
_JOINT_SPEED = 1.2  #: rad/s along a planned path
_TORSO_SPEED = 0.15  #: m/s
_LIFT = 0.12  #: metres the object is lifted after closing
_RISEN = 0.05  #: metres the hand must have risen for the object to count as lifted
_ARRIVED = 0.1  #: radians (metres for the torso) from the carry pose: the arm got there
_CARRY_REACH = 0.45  #: metres from the base's centre where the hand carries an object
GRIP_FORCE = 20.0  #: newtons per finger
_GRAVITY = 9.81
_EMPTY_WIDTH = 0.006  #: fingers closer than this hold nothing
#: the wrist must feel at least this share of the object's weight (when its mass is known)
_WEIGHT_SHARE = 0.4


class Manipulator(Protocol):
    """What picking needs of a body: the arm, the gripper, the wrist sensor and ticks."""

    tick_period: float

    def now(self) -> float: ...

    def tick(self, ticks: int = 1) -> None: ...

    def arm(self) -> Arm: ...

    def gripper(self) -> Gripper: ...

    def wrist_wrench(self) -> Wrench: ...


class PickOutcome(StrEnum):
    """How a pick ended."""

    HELD = "held"  #: the gripper and the wrist sense the object in the hand
    NOT_HELD = "not_held"  #: the arm moved, but the hand is empty or lost the object
    UNREACHABLE = "unreachable"  #: no grasp is kinematically feasible and collision-free
    NO_PATH = "no_path"  #: grasps exist but the arm found no free way to them
    TOO_HEAVY = "too_heavy"  #: the object weighs more than the arm's payload
    #: every grasp found has been tried on the object, and each left the hand empty
    TRIED_ALL = "tried_all"


@dataclass(frozen=True)
class PickPlan:
    """A planned pick: the grasp and the reach path (configurations, torso first)."""

    grasp: Grasp
    path: list[np.ndarray]
    lift: np.ndarray
    carry: np.ndarray  #: raised and drawn back: where the object is held afterwards
    planning_seconds: float  #: CPU seconds for grasp selection and RRT
    rise: float = 0.0  #: metres the hand is higher at ``carry`` than at the grasp


@dataclass(frozen=True)
class PickResult:
    """What a pick did and sensed."""

    outcome: PickOutcome
    plan: PickPlan | None = None
    width: float = 0.0
    weight: float = 0.0  #: newtons the wrist felt added
    detail: str = ""
    planning_seconds: float = 0.0
    log: list[str] = field(default_factory=list)

    def __bool__(self) -> bool:
        return self.outcome is PickOutcome.HELD


def current_configuration(body: Manipulator) -> np.ndarray:
    state = body.arm().state()
    return np.array([state.torso, *state.positions])


def plan_motion(scene: PlanningScene, start: np.ndarray, goal: np.ndarray,
                rng: np.random.Generator, *, gripper: float = 0.2,
                allowed: frozenset[str] = frozenset()) -> list[np.ndarray] | None:
    """A smoothed collision-free path from ``start`` to ``goal``, or None."""
    def valid(q: np.ndarray) -> bool:
        return not scene.collides(q, gripper=gripper, allowed=allowed)

    if not valid(goal):
        return None
    if not valid(start):  # starting in contact (e.g. just let go): tolerate it nearby
        def valid(q: np.ndarray) -> bool:
            return float(np.max(np.abs(q - start))) < _ESCAPE or \
                not scene.collides(q, gripper=gripper, allowed=allowed)
    path = rrt_connect(start, goal, valid, scene.lower, scene.upper, rng)
    return None if path is None else shortcut(path, valid, rng)


def plan_pick(scene: PlanningScene, obj: ObjectGeometry, current: np.ndarray,
              rng: np.random.Generator, *, mass: float | None = None,
              payload: float = float("inf"),
              avoid: Sequence[GraspCandidate] = ()) -> PickPlan | PickResult:
    """Select a grasp for ``obj`` (none like those in ``avoid``, which failed) and plan the
    reach to its pre-grasp."""
    started = time.process_time()
    if mass is not None and mass > payload:
        return PickResult(PickOutcome.TOO_HEAVY,
                          detail=f"{obj.name} weighs {mass:.2f} kg, above the arm's payload "
                                 f"of {payload:.2f} kg")
    grasp = select_grasp(scene, obj, current, avoid=avoid)
    if grasp is None:
        return PickResult(PickOutcome.UNREACHABLE,
                          detail=f"no feasible grasp for {obj.name} from here",
                          planning_seconds=time.process_time() - started)
    path = plan_motion(scene, current, grasp.pre_grasp, rng, gripper=grasp.candidate.opening())
    at, rotation = scene.grasp_frame(grasp.grasp)
    lift = _lift(scene, grasp.grasp, at, rotation)
    carry = carry_pose(scene, lift, rotation)
    rise = float(scene.grasp_frame(carry)[0][2] - at[2])
    seconds = time.process_time() - started
    if path is None:
        return PickResult(PickOutcome.NO_PATH, detail=f"no collision-free reach to {obj.name}",
                          planning_seconds=seconds)
    return PickPlan(grasp, path, lift, carry, seconds, rise)


def _lift(scene: PlanningScene, grasp: np.ndarray, at: np.ndarray,
          rotation: np.ndarray) -> np.ndarray:
    """Straight up from the grasp: by the torso where it has room (a pure vertical lift),
    else by IK, else as high as IK reaches in smaller steps."""
    room = float(scene.upper[0]) - float(grasp[0])
    if room >= _LIFT:
        lifted = grasp.copy()
        lifted[0] += _LIFT
        return lifted
    for rise in (_LIFT, 0.08, 0.05):
        found = solve_ik(scene, at + np.array([0.0, 0.0, rise]), rotation, [grasp])
        if found is not None:
            return found
    lifted = grasp.copy()
    lifted[0] = scene.upper[0]
    return lifted


def carry_pose(scene: PlanningScene, lift: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    """The hand at ``lift`` raised further and drawn back towards the base, keeping its
    grip's orientation (an upright bottle stays upright): where an object is carried; the
    torso raised when IK finds none."""
    at, _ = scene.grasp_frame(lift)
    base = np.array(scene.base[:2])
    reach = at[:2] - base
    distance = float(np.linalg.norm(reach))
    back = base + reach * (max(_CARRY_REACH, distance - 0.15) / max(distance, 1e-9))
    target = np.array([*back, at[2] + 0.1])
    carry = solve_ik(scene, target, rotation, [lift])
    if carry is None:
        carry = lift.copy()
        carry[0] = scene.upper[0]
    return carry


def follow(body: Manipulator, path: Sequence[np.ndarray], *, settle: float = 0.3) -> None:
    """Drive the arm along ``path`` (torso first in each configuration), tick by tick."""
    dt = body.tick_period
    here = np.array(path[0], dtype=float)
    for waypoint in path[1:]:
        target = np.array(waypoint, dtype=float)
        gap = target - here
        duration = max(float(np.max(np.abs(gap[1:]))) / _JOINT_SPEED,
                       abs(float(gap[0])) / _TORSO_SPEED, dt)
        steps = max(1, int(np.ceil(duration / dt)))
        for step in range(1, steps + 1):
            q = here + gap * (step / steps)
            body.arm().command(JointTarget(tuple(q[1:]), torso=float(q[0])))
            body.tick()
        here = target
    body.tick(max(1, round(settle / dt)))


def execute_pick(body: Manipulator, plan: PickPlan, *, mass: float | None = None) -> PickResult:
    """Reach, move in, close, lift and retract; then sense whether the object is held."""
    log: list[str] = []
    grasp = plan.grasp
    body.gripper().command(grasp.candidate.opening())
    follow(body, plan.path)
    before = float(np.linalg.norm(body.wrist_wrench().force))
    follow(body, [plan.path[-1], grasp.grasp], settle=0.2)
    body.gripper().command(0.0, GRIP_FORCE)
    body.tick(max(1, round(0.6 / body.tick_period)))
    follow(body, [grasp.grasp, plan.lift], settle=0.3)
    width = body.gripper().state().width
    weight = float(np.linalg.norm(body.wrist_wrench().force)) - before
    log.append(f"lifted: width {width:.3f} m, wrist {weight:+.2f} N")
    follow(body, [plan.lift, plan.carry], settle=0.3)
    width = body.gripper().state().width
    weight = float(np.linalg.norm(body.wrist_wrench().force)) - before
    log.append(f"carrying: width {width:.3f} m, wrist {weight:+.2f} N")
    sensed = current_configuration(body)
    # proprioception: the hand rose with the object (the arm got where it was sent)
    held = width > _EMPTY_WIDTH and plan.rise >= _RISEN and \
        float(np.max(np.abs(sensed - plan.carry))) < _ARRIVED
    if held and mass is not None:
        held = weight > _WEIGHT_SHARE * mass * _GRAVITY
    return PickResult(PickOutcome.HELD if held else PickOutcome.NOT_HELD, plan, width, weight,
                      planning_seconds=plan.planning_seconds, log=log)
