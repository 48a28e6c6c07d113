"""Task-space compliance with per-axis stiffness (Cosero §4.2), mapped to joint torques.

The hand is held at a target pose in the robot's base frame (REP 103: x forward, y left,
z up; then roll, pitch, yaw). Each of the six task dimensions is a spring and damper
whose holding force is limited. A dimension that is not compliant holds with up to
``max_force``; a compliant one follows Cosero's scaling: its *compliance* ``c`` falls
linearly from 1 (at the target) to 0 (``span`` away), and its holding force rises from
``min_force`` (fully compliant) to ``max_force`` (not compliant) as ``c`` falls. Each
dimension is compliant in the positive and the negative direction separately, so the
hand can yield upwards and stay stiff downwards. Pushed by a steady force ``F``
between the two limits, a compliant dimension comes to rest
``span · (F - min_force) / (max_force - min_force)`` from its target: what the
interaction behaviours (``homebot.manipulation.interaction``) read as the person's
intention.

The task wrench goes to the joints through the Jacobian transpose; gravity is
compensated, and a joint-space spring in the Jacobian's null space keeps the redundant
seventh joint near a rest posture. Everything here is arrays in and arrays out, from
what the arm's drivers report (joint state, hand pose, Jacobian, gravity torques); it
never reads the simulator.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np
from scipy.spatial.transform import Rotation

__all__ = [
    "TASK_AXES",
    "ArmReading",
    "AxisCompliance",
    "Compliance",
    "ComplianceController",
    "displacement",
    "joint_torques",
    "task_wrench",
]

#: The task dimensions in the base frame, in the order every 6-vector here uses.
TASK_AXES = ("x", "y", "z", "roll", "pitch", "yaw")


@dataclass(frozen=True)
class AxisCompliance:
    """One task dimension: a spring and damper with a limited holding force.

    Units are newtons and metres for x, y, z; newton-metres and radians for the rotations.
    """

    stiffness: float  #: spring constant inside the force limit
    damping: float  #: per m/s (or rad/s)
    max_force: float  #: holding force when not compliant
    min_force: float = 0.0  #: holding force when fully compliant (at the target)
    span: float = 0.1  #: displacement at which a compliant dimension is stiff again
    positive: bool = False  #: compliant when displaced in the positive direction
    negative: bool = False  #: compliant when displaced in the negative direction

    def __post_init__(self) -> None:
        values = (self.stiffness, self.damping, self.max_force, self.min_force, self.span)
        if not all(np.isfinite(v) and v >= 0 for v in values) or self.span <= 0:
            raise ValueError(f"compliance needs finite, non-negative gains and a positive "
                             f"span: {self}")
        if self.min_force > self.max_force:
            raise ValueError(f"min_force {self.min_force} exceeds max_force {self.max_force}")

    def compliant(self, shift: float) -> bool:
        """Whether the dimension yields to a displacement ``shift`` (its sign matters)."""
        return (shift > 0 and self.positive) or (shift < 0 and self.negative)

    def limit(self, shift: float) -> float:
        """The holding force at displacement ``shift``."""
        if not self.compliant(shift):
            return self.max_force
        c = float(np.clip(1.0 - abs(shift) / self.span, 0.0, 1.0))
        return self.min_force + (1.0 - c) * (self.max_force - self.min_force)

    def rest_shift(self, force: float) -> float:
        """Where a steady push ``force`` (signed) leaves the dimension, ignoring the inner
        spring: 0 below ``min_force``, ``span`` at ``max_force`` or more."""
        if not self.compliant(force) or abs(force) <= self.min_force:
            return 0.0
        rise = self.max_force - self.min_force
        fraction = 1.0 if rise <= 0 else min(1.0, (abs(force) - self.min_force) / rise)
        return float(np.sign(force)) * fraction * self.span


_LINEAR = AxisCompliance(stiffness=1500.0, damping=60.0, max_force=80.0, min_force=2.0,
                         span=0.12)
_ANGULAR = AxisCompliance(stiffness=60.0, damping=3.0, max_force=15.0, min_force=0.2,
                          span=0.5)


@dataclass(frozen=True)
class Compliance:
    """The six task dimensions, and the rest posture of the null space."""

    axes: tuple[AxisCompliance, ...] = (_LINEAR,) * 3 + (_ANGULAR,) * 3
    null_stiffness: float = 8.0  #: N·m/rad towards the rest posture
    null_damping: float = 1.5  #: N·m·s/rad

    def __post_init__(self) -> None:
        if len(self.axes) != 6:
            raise ValueError(f"compliance has one setting per task axis {TASK_AXES}")

    @classmethod
    def stiff(cls) -> Compliance:
        """Position control in all six dimensions."""
        return cls()

    def with_axes(self, **changes: Mapping[str, float | bool] | AxisCompliance) -> Compliance:
        """A copy with some dimensions changed, by name (``x=…``, ``pitch=…``): an
        ``AxisCompliance``, or a mapping of its fields to change."""
        axes = list(self.axes)
        for name, change in changes.items():
            if name not in TASK_AXES:
                raise ValueError(f"unknown task axis '{name}'; axes: {', '.join(TASK_AXES)}")
            index = TASK_AXES.index(name)
            axes[index] = change if isinstance(change, AxisCompliance) else replace(
                axes[index], **dict(change))  # type: ignore[arg-type]
        return replace(self, axes=tuple(axes))

    def compliant_in(self, *names: str, positive: bool = True,
                     negative: bool = True) -> Compliance:
        """A copy with the named dimensions compliant in the given directions."""
        return self.with_axes(**{name: {"positive": positive, "negative": negative}
                                 for name in names})


@dataclass(frozen=True)
class ArmReading:
    """What the arm's drivers report, in the base frame.

    ``jacobian`` is 6 × n (linear rows, then angular) for the hand's point; ``gravity``
    the joint torques that hold the arm (and what it carries) against gravity.
    """

    q: np.ndarray
    qd: np.ndarray
    hand_position: np.ndarray
    hand_rotation: np.ndarray  #: 3 × 3
    jacobian: np.ndarray
    gravity: np.ndarray

    @property
    def hand_twist(self) -> np.ndarray:
        """The hand's linear and angular velocity."""
        twist: np.ndarray = self.jacobian @ self.qd
        return twist


def displacement(position: np.ndarray, rotation: np.ndarray, target_position: np.ndarray,
                 target_rotation: np.ndarray) -> np.ndarray:
    """How far the hand is from its target: position minus target, and the rotation
    vector that turns the target's orientation into the hand's (both in the base frame)."""
    turn = Rotation.from_matrix(rotation @ np.asarray(target_rotation).T).as_rotvec()
    return np.concatenate((np.asarray(position) - np.asarray(target_position), turn))


def task_wrench(compliance: Compliance, shift: np.ndarray, twist: np.ndarray) -> np.ndarray:
    """The force and torque the hand exerts to get back to its target, per dimension:
    spring within the (compliance-scaled) holding limit, plus damping."""
    wrench = np.empty(6)
    for i, axis in enumerate(compliance.axes):
        limit = axis.limit(float(shift[i]))
        spring = float(np.clip(-axis.stiffness * shift[i], -limit, limit))
        wrench[i] = spring - axis.damping * twist[i]
    return wrench


def joint_torques(state: ArmReading, wrench: np.ndarray, compliance: Compliance,
                  rest: np.ndarray | None = None) -> np.ndarray:
    """``Jᵀ·wrench`` plus gravity, plus a rest-posture spring projected into the null space
    (so it does not disturb the hand)."""
    jacobian = state.jacobian
    tau = jacobian.T @ wrench + state.gravity
    n = jacobian.shape[1]
    if rest is not None and n > 6:
        posture = compliance.null_stiffness * (rest - state.q) - compliance.null_damping * state.qd
        pinv = np.linalg.pinv(jacobian, rcond=1e-3)
        projector = np.eye(n) - jacobian.T @ pinv.T
        tau = tau + projector @ posture
    elif n <= 6:
        tau = tau - compliance.null_damping * state.qd
    result: np.ndarray = tau
    return result


class ComplianceController:
    """Holds the hand at a target pose with the given compliance.

    Call ``torques(state)`` once per control tick; change ``target`` and ``compliance``
    between ticks. ``shift`` (the last displacement from the target) and ``wrench`` are
    kept for the behaviours that watch them.
    """

    def __init__(self, compliance: Compliance, target_position: np.ndarray,
                 target_rotation: np.ndarray, rest: np.ndarray | None = None) -> None:
        self.compliance = compliance
        self.target_position = np.asarray(target_position, dtype=float).copy()
        self.target_rotation = np.asarray(target_rotation, dtype=float).copy()
        self.rest = None if rest is None else np.asarray(rest, dtype=float).copy()
        self.shift = np.zeros(6)
        self.wrench = np.zeros(6)

    def torques(self, state: ArmReading) -> np.ndarray:
        self.shift = displacement(state.hand_position, state.hand_rotation,
                                  self.target_position, self.target_rotation)
        self.wrench = task_wrench(self.compliance, self.shift, state.hand_twist)
        return joint_torques(state, self.wrench, self.compliance, self.rest)
