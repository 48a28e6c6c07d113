"""``ArmedBodyRobot``: the embodied robot whose grasps and releases run its arm in physics.

A grasp plans a grasp and an arm motion (``homebot.manipulation``), moves the arm, closes
the gripper and lifts; whether the object is then in the hand is what the gripper and the
wrist sense, and what the simulator's physics made of the grasp, never a die. When no
grasp is feasible from where the robot stands, it steps to the surface's edge in front of
the object and tries once more. A release puts the object on a free spot of the placement
(or drops it into a bin). The robot has one arm: the world's second hand name is kept for
the skills, but a grasp with the gripper full is refused (the hand stays empty).
"""

from __future__ import annotations

import math
from typing import Any

from shapely.geometry import Point

from homebot.embodied.robot import BodyRobot
from homebot.manipulation.control import ArmControl
from homebot.manipulation.pick import PickOutcome
from homebot.robot import Detection, Pose

__all__ = ["ArmedBodyRobot"]

_STAND_OFF = 0.4  #: metres from a surface's edge where the robot stands to reach over it
_BIN_CATEGORIES = ("bin", "trash", "trash can", "waste bin")


class ArmedBodyRobot(BodyRobot):
    """A ``BodyRobot`` that grasps, holds and releases with its arm.

    Args:
        *args: as ``BodyRobot``.
        arm: picking and placing over the same body.
        **kwargs: as ``BodyRobot``.
    """

    def __init__(self, *args: Any, arm: ArmControl, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.arm = arm
        self._holding: dict[str, Detection] = {}

    def grasp(self, detection: Detection, hand: str) -> None:
        if hand in self._holding:
            return
        result = self.arm.pick(detection.label, self.pose(), detection.position, detection.mass)
        if result.outcome is PickOutcome.UNREACHABLE:
            stand = self._stand_before(detection.label, detection.position)
            if stand is not None and self.move_to(stand).reached:
                result = self.arm.pick(detection.label, self.pose(), detection.position,
                                       detection.mass)
        self.events.record("robot.pick", object=detection.label, outcome=result.outcome.value,
                           detail=result.detail,
                           planning=round(result.planning_seconds, 4))
        if result:
            self._holding[hand] = detection

    def held(self, hand: str) -> Detection | None:
        detection = self._holding.get(hand)
        if detection is not None and not self.arm.gripper_holds():
            self.arm.holding = None  # it slipped out: the fingers closed on nothing
            del self._holding[hand]
            return None
        return detection

    def release(self, hand: str, placement: str) -> None:
        if self._holding.pop(hand, None) is None:
            return
        known = self.world.placements.get(placement)
        done = False
        if known is not None:
            category = known.model.category.lower()
            outcome = self.arm.place(placement, self.pose(), drop=category in _BIN_CATEGORIES)
            self.events.record("robot.place", placement=placement, done=outcome.done,
                               detail=outcome.detail)
            done = outcome.done
        if not done:  # no spot: let go where the hand is; what happens is physics'
            self.body.gripper().command(0.2)
            self.body.tick(max(1, round(0.5 / self.body.tick_period)))
            self.arm.holding = None

    def hand_over(self, hand: str, person: str) -> bool:
        given = super().hand_over(hand, person)
        if given and self._holding.pop(hand, None) is not None:
            self.body.gripper().command(0.2)  # the person holds it: open the fingers
            self.arm.holding = None
        return given

    def _stand_before(self, name: str, seen_at: tuple[float, float] | None) -> Pose | None:
        """A pose at the edge of the object's surface nearest to it, facing it."""
        where = self.arm.locate(name)
        point = seen_at if seen_at is not None else (where[:2] if where else None)
        if point is None:
            return None
        found = [(p.footprint.distance(Point(point)), p) for p in self.world.placements.values()
                 if p.footprint.covers(Point(point))]
        if not found:
            return None
        footprint = min(found, key=lambda pair: pair[0])[1].footprint
        ring = footprint.exterior
        edge = ring.interpolate(ring.project(Point(point)))
        dx, dy = edge.x - point[0], edge.y - point[1]
        norm = math.hypot(dx, dy) or 1.0
        x, y = edge.x + dx / norm * _STAND_OFF, edge.y + dy / norm * _STAND_OFF
        if self.world.footprint_problem(x, y) is not None:
            return None
        return Pose(x, y, math.atan2(point[1] - y, point[0] - x))
