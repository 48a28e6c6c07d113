"""Tool use: watering a plant with a watering can (Cosero §6.4.3).

Cosero grasps a known can at a predefined reference pose, drives to a pose in front of
the plant, places itself relative to the pot it sees in its laser, and pours by moving
the can's spout in a predetermined way. Here the can is a ``Tool``: the pose of its end
effector (the spout's tip) in the hand's frame, known from the can's model and the
grasp. The robot extends its kinematic chain with it (§6.4.1): a spout pose the motion
wants becomes a hand pose, ``hand = spout · tip⁻¹``. ``WateringMotion`` holds the spout
above the pot and tips the can about the spout's tip (about the tool's ``axis``: a
parallel gripper holds a can firmly against a roll of the wrist, weakly against a pitch
about the fingers' axis), so the water falls where the tip is while the can turns; then
tips it back.

Everything is in the robot's base frame and arrays in, arrays out; nothing here reads
the simulator.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

__all__ = ["PourPhase", "Tool", "WateringMotion", "approach_offset", "turn"]


def turn(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    """The rotation by ``angle`` about a unit ``axis`` (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    cross = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    rotation: np.ndarray = np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * (
        cross @ cross)
    return rotation


@dataclass(frozen=True)
class Tool:
    """A grasped tool: where its end effector is in the hand's frame."""

    name: str
    tip: tuple[float, float, float]  #: the end effector's position in the hand frame (m)
    #: the hand-frame axis the tool is turned about to use it (positive: the tip goes down)
    axis: tuple[float, float, float] = (0.0, 1.0, 0.0)

    def hand_for(self, tip_position: np.ndarray, rotation: np.ndarray) -> np.ndarray:
        """Where the hand must be so the tip is at ``tip_position`` with the hand (and
        tool) turned by ``rotation``."""
        hand: np.ndarray = np.asarray(tip_position, dtype=float) - rotation @ np.asarray(
            self.tip, dtype=float)
        return hand


class PourPhase(StrEnum):
    """Where a ``WateringMotion`` is."""

    APPROACH = "approach"  #: moving the level can so its spout is above the pot
    TIPPING = "tipping"  #: turning the can about the spout's tip
    POURING = "pouring"  #: holding it tipped
    RIGHTING = "righting"  #: turning it back level
    DONE = "done"


class WateringMotion:
    """The pouring primitive, parameterised by where the pot is (base frame).

    Args:
        tool: the grasped can.
        start: the hand's position when the motion begins (can level).
        rotation: the hand's orientation with the can level.
        pot: the pot's rim centre, as the robot perceives it.
        clearance: metres the spout's tip stays above the rim.
        angle: how far the can is tipped (rad).
        pour_time: seconds it is held tipped.
        speed: metres per second of the approach; ``turn_rate`` rad/s of tipping.
    """

    def __init__(self, tool: Tool, start: np.ndarray, rotation: np.ndarray, pot: np.ndarray,
                 *, clearance: float = 0.1, angle: float = 1.0, pour_time: float = 3.0,
                 speed: float = 0.15, turn_rate: float = 0.4) -> None:
        self.tool = tool
        self.rotation = np.asarray(rotation, dtype=float)
        self.start = np.asarray(start, dtype=float)
        self.above = np.asarray(pot, dtype=float) + np.array([0.0, 0.0, clearance])
        self.angle, self.pour_time = angle, pour_time
        self.speed, self.turn_rate = speed, turn_rate
        self.phase = PourPhase.APPROACH
        self.elapsed = 0.0
        self._approach = tool.hand_for(self.above, self.rotation)
        self._distance = float(np.linalg.norm(self._approach - self.start))

    def tilt_at(self) -> float:
        """The tipping angle the motion wants now."""
        if self.phase is PourPhase.TIPPING:
            return min(self.angle, self.turn_rate * self.elapsed)
        if self.phase is PourPhase.POURING:
            return self.angle
        if self.phase is PourPhase.RIGHTING:
            return max(0.0, self.angle - self.turn_rate * self.elapsed)
        return 0.0

    def update(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """The hand's target pose (position, rotation) after ``dt`` more seconds."""
        self.elapsed += dt
        if self.phase is PourPhase.APPROACH:
            done = self.speed * self.elapsed
            if done >= self._distance:
                self.phase, self.elapsed = PourPhase.TIPPING, 0.0
            else:
                f = done / self._distance if self._distance > 0 else 1.0
                return self.start + f * (self._approach - self.start), self.rotation
        if self.phase is PourPhase.TIPPING and self.turn_rate * self.elapsed >= self.angle:
            self.phase, self.elapsed = PourPhase.POURING, 0.0
        elif self.phase is PourPhase.POURING and self.elapsed >= self.pour_time:
            self.phase, self.elapsed = PourPhase.RIGHTING, 0.0
        elif self.phase is PourPhase.RIGHTING and self.turn_rate * self.elapsed >= self.angle:
            self.phase = PourPhase.DONE
        turned = self.rotation @ turn(self.tool.axis, self.tilt_at())
        return self.tool.hand_for(self.above, turned), turned


def approach_offset(tool: Tool, hand: np.ndarray) -> np.ndarray:
    """Where the pot should be relative to the base (x, y) so the level can's spout is
    above it with the hand at ``hand``: the base stands there before pouring."""
    tip = np.asarray(hand, dtype=float) + np.asarray(tool.tip, dtype=float)
    offset: np.ndarray = tip[:2]
    return offset
