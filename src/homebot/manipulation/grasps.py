"""Grasp planning after Cosero (§6.2): top and side grasps from an object's principal axes.

An object is described by its principal axes in the horizontal plane, its extents along
them and its height above the surface, computed from a point cloud cluster
(``ObjectGeometry.from_points``) or from a catalogue shape at a known pose
(``ObjectGeometry.from_shape``). Top grasps approach low objects from above, closing across
a principal axis; side grasps approach vertically elongated ones horizontally from the
robot's side. Candidates are ranked by efficiency and robustness criteria (the kind that
suits the object's proportions, an approach from the robot's side, a grasp near the centre
of mass, a comfortable width), then checked in rank order for kinematic feasibility (IK of
pre-grasp and grasp) and collisions, as Cosero does. A flat object gets no side grasp: the
fingers, which cannot go lower beside it, would hold its top edge only. A round object's
top grasps close across the line of sight, along it and on the diagonals between: a wide
round thing (a plate) leaves the fingers a centimetre or two to spare, so a grasp aimed
where perception was off along its closing axis misses, and one across another axis may
not. Grasps like one that already failed (``GraspCandidate.resembles``) can be left out of
the choice.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from homebot.manipulation.ik import solve_ik
from homebot.manipulation.scene import PlanningScene

__all__ = ["IK_SEEDS", "Grasp", "GraspCandidate", "ObjectGeometry", "grasp_candidates",
           "select_grasp"]

MAX_WIDTH = 0.2  #: the gripper's widest opening, metres
_WIDTH_MARGIN = 0.04  #: the fingers open this much wider than the object before closing
_PRE_GRASP = 0.1  #: metres back along the approach where the hand stops before going in
_FINGER_TIP = 0.025  #: metres the finger tips reach beyond the grasp site
_PALM = 0.065  #: metres from the grasp site back to the palm
_FINGER_HALF_HEIGHT = 0.015
_TABLE_CLEARANCE = 0.012  #: metres the fingers keep above the surface
#: torso heights tried for a grasp, each leaving room to lift the object by the torso
_TORSO_LEVELS = (0.25, 0.38, 0.1)
_SIDE_YAWS = np.radians([-50.0, -25.0, 0.0, 25.0, 50.0])
#: a round object's top grasps close at these angles to the line of sight (across it first),
#: each ranked down by its penalty
_ROUND_TOP_CLOSINGS = ((math.radians(90.0), 0.0), (0.0, 0.1), (math.radians(45.0), 0.3),
                       (math.radians(135.0), 0.35))
_SAME_AIM = 0.03  #: metres between two grasps' sites for them to aim at the same place
_SAME_AXIS = math.radians(30.0)  #: radians between closing axes (or approaches) alike
#: IK starts besides the arm's current configuration: bent forward over a table, hand
#: down (top grasps) and hand level (side grasps); torso first
IK_SEEDS = (np.array([0.2, 0.0, -1.2, 0.0, 2.3, 0.0, 0.6, 0.0]),
             np.array([0.2, 0.0, 0.3, 0.0, 1.0, 0.0, -1.2, 0.0]))


@dataclass(frozen=True)
class ObjectGeometry:
    """An object for grasping: its centre, horizontal principal axes and extents, height.

    ``axes[0]`` is the major horizontal axis (unit vector on the map), ``axes[1]`` the
    minor; ``extents`` are the object's sizes along them; ``base`` is the surface's height.
    """

    name: str
    center: np.ndarray  #: (x, y) on the map
    axes: np.ndarray  #: 2×2, rows are unit vectors
    extents: tuple[float, float]
    height: float
    base: float
    round: bool = False  #: a cylinder or sphere: any horizontal axis is principal

    @classmethod
    def from_points(cls, name: str, points: np.ndarray, base: float) -> ObjectGeometry:
        """From a cluster of 3-D points (map frame) on a surface at height ``base``."""
        xy = points[:, :2]
        middle = xy.mean(axis=0)
        _, vectors = np.linalg.eigh(np.cov((xy - middle).T))
        axes = np.array([vectors[:, 1], vectors[:, 0]])  # eigh sorts ascending
        spans = (xy - middle) @ axes.T
        low, high = spans.min(axis=0), spans.max(axis=0)
        center = middle + axes.T @ ((low + high) / 2)
        extents = (float(high[0] - low[0]), float(high[1] - low[1]))
        return cls(name, center, axes, extents, float(points[:, 2].max() - base), base,
                   round=extents[1] > 0.85 * extents[0])

    @classmethod
    def from_shape(cls, name: str, shape: str, extent: tuple[float, float, float],
                   position: tuple[float, float], yaw: float, base: float) -> ObjectGeometry:
        """From a catalogue shape (box, cylinder, sphere) standing at ``position``."""
        x, y, z = extent
        along = np.array([math.cos(yaw), math.sin(yaw)])
        across = np.array([-along[1], along[0]])
        axes, extents = (np.array([along, across]), (x, y)) if x >= y else \
            (np.array([across, along]), (y, x))
        return cls(name, np.array(position, dtype=float), axes, extents, z, base,
                   round=shape != "box")


@dataclass(frozen=True)
class GraspCandidate:
    """A grasp pose of the grasp site: position, rotation (x: approach, y: closing axis)."""

    kind: Literal["top", "side"]
    position: np.ndarray
    rotation: np.ndarray
    width: float  #: the object's width between the fingers
    score: float

    def pre_grasp(self) -> np.ndarray:
        """Where the hand waits before moving in along its approach."""
        return self.position - _PRE_GRASP * self.rotation[:, 0]

    def opening(self) -> float:
        return min(MAX_WIDTH, self.width + _WIDTH_MARGIN)

    def resembles(self, other: GraspCandidate) -> bool:
        """Whether this grasp is, for the object, the same as ``other``: of the same kind,
        aimed within ``_SAME_AIM`` of it, approaching alike and closing along the same line
        (the fingers swapped, or the wrist rolled half a turn, change nothing)."""
        if self.kind != other.kind or \
                float(np.linalg.norm(self.position - other.position)) > _SAME_AIM:
            return False
        approach = float(self.rotation[:, 0] @ other.rotation[:, 0])
        closing = abs(float(self.rotation[:, 1] @ other.rotation[:, 1]))
        return approach >= math.cos(_SAME_AXIS) and closing >= math.cos(_SAME_AXIS)


@dataclass(frozen=True)
class Grasp:
    """A feasible grasp: the candidate with its pre-grasp and grasp configurations."""

    candidate: GraspCandidate
    pre_grasp: np.ndarray
    grasp: np.ndarray


def _frame(approach: np.ndarray, closing: np.ndarray) -> np.ndarray:
    x = approach / np.linalg.norm(approach)
    y = closing - x * float(closing @ x)
    y /= np.linalg.norm(y)
    return np.column_stack((x, y, np.cross(x, y)))


def grasp_candidates(obj: ObjectGeometry, robot: np.ndarray) -> list[GraspCandidate]:
    """Top and side grasp candidates for ``obj``, best first.

    ``robot`` is where the robot stands (x, y on the map): side grasps come from its side.
    """
    found: list[GraspCandidate] = []
    top_z = obj.base + obj.height
    towards = obj.center - robot[:2]
    towards /= max(float(np.linalg.norm(towards)), 1e-9)
    tall = obj.height > 1.2 * obj.extents[1]
    # top grasps: straight down, closing across the minor (then the major) axis; a round
    # object's across the line of sight, along it, then on the diagonals
    z = max(top_z - min(0.035, obj.height / 2), obj.base + _FINGER_TIP + _TABLE_CLEARANCE)
    closings: list[tuple[np.ndarray, float, float]] = []  # (axis, width, penalty)
    if obj.round:
        for angle, penalty in _ROUND_TOP_CLOSINGS:
            c, s = math.cos(angle), math.sin(angle)
            # the wider extent: a cluster's round outline is seldom quite round
            closings.append((np.array([c * towards[0] - s * towards[1],
                                       s * towards[0] + c * towards[1]]), obj.extents[0],
                             penalty))
    else:
        closings = [(obj.axes[1], obj.extents[1], 0.0), (obj.axes[0], obj.extents[0], 0.1)]
    for axis, width, penalty in closings:
        if width + 0.01 > MAX_WIDTH:
            continue
        for sign in (1.0, -1.0):
            closing = np.array([*(sign * axis), 0.0])
            rotation = _frame(np.array([0.0, 0.0, -1.0]), closing)
            # the palm faces forward-ish: prefer the wrist roll that keeps x of the hand's
            # z axis along the reach
            comfort = float(rotation[:2, 2] @ towards)
            score = (1.0 if not tall else 0.4) + 0.2 * comfort - 0.5 * width - penalty
            found.append(GraspCandidate("top", np.array([*obj.center, z]), rotation, width,
                                        score))
    # side grasps: horizontal approach from the robot's side, closing horizontally
    z = obj.base + max(min(obj.height / 2, 0.08), _FINGER_HALF_HEIGHT + _TABLE_CLEARANCE + 0.02)
    directions: list[tuple[np.ndarray, float]] = []
    if obj.round:
        for yaw in _SIDE_YAWS:
            c, s = math.cos(yaw), math.sin(yaw)
            directions.append((np.array([c * towards[0] - s * towards[1],
                                         s * towards[0] + c * towards[1]]), obj.extents[1]))
    else:
        for index in (0, 1):
            for sign in (1.0, -1.0):
                # approaching along one axis closes across the other
                directions.append((sign * obj.axes[index], obj.extents[1 - index]))
    # Lower than the hand can go beside it, a flat thing would be held by its top edge
    # alone, and it tips out of the fingers once the hand turns (held out to a person).
    if obj.height < z - obj.base + _FINGER_HALF_HEIGHT:
        directions = []
    for direction, width in directions:
        facing = float(direction @ towards)
        if facing < 0.3 or width + 0.01 > MAX_WIDTH:
            continue
        depth = obj.extents[0] if obj.round else \
            float(abs(direction @ obj.axes[0]) * obj.extents[0] +
                  abs(direction @ obj.axes[1]) * obj.extents[1])
        back = max(0.0, depth / 2 + 0.01 - _PALM)
        approach = np.array([*direction, 0.0])
        closing = np.array([-direction[1], direction[0], 0.0])
        position = np.array([*obj.center, z]) - back * approach
        score = (1.0 if tall else 0.6) + 0.3 * facing - 0.5 * width - 0.3 * back
        found.append(GraspCandidate("side", position, _frame(approach, closing), width, score))
    found.sort(key=lambda g: -g.score)
    return found


def select_grasp(scene: PlanningScene, obj: ObjectGeometry, current: np.ndarray,
                 *, keep: int = 3, budget: int = 12,
                 avoid: Sequence[GraspCandidate] = ()) -> Grasp | None:
    """The best feasible grasp: candidates in rank order, IK for the pre-grasp and the
    grasp, both free of collisions (the gripper may touch ``obj`` only at the grasp);
    of the first ``keep`` feasible ones the one nearest ``current`` in joint space wins.
    A candidate that resembles one in ``avoid`` (grasps that failed) is left out."""
    feasible: list[tuple[float, Grasp]] = []
    allowed = scene.without([obj.name])
    candidates = [candidate for candidate in grasp_candidates(obj, np.array(scene.base[:2]))
                  if not any(candidate.resembles(failed) for failed in avoid)]
    for candidate in candidates[:budget]:
        found = _feasible(scene, candidate, current, allowed)
        if found is None:
            continue
        pre, grasp = found
        travel = float(np.linalg.norm(pre - current))
        feasible.append((candidate.score - 0.05 * travel, Grasp(candidate, pre, grasp)))
        if len(feasible) >= keep:
            break
    if not feasible:
        return None
    return max(feasible, key=lambda pair: pair[0])[1]


def _feasible(scene: PlanningScene, candidate: GraspCandidate, current: np.ndarray,
              allowed: frozenset[str]) -> tuple[np.ndarray, np.ndarray] | None:
    """Collision-free IK solutions for the grasp and its pre-grasp, trying each seed
    (the current configuration first), or None."""
    opening = candidate.opening()
    for torso in _TORSO_LEVELS:
        for seed in (current, *IK_SEEDS):
            grasp = solve_ik(scene, candidate.position, candidate.rotation, [seed],
                             posture=seed, torso=torso)
            if grasp is None or scene.collides(grasp, gripper=opening, allowed=allowed):
                continue
            pre = solve_ik(scene, candidate.pre_grasp(), candidate.rotation, [grasp])
            if pre is None or scene.collides(pre, gripper=opening):
                continue
            return pre, grasp
    return None
