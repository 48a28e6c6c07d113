"""Inverse kinematics: damped least squares on MuJoCo's Jacobian of the grasp site."""

from __future__ import annotations

import numpy as np

from homebot.manipulation.scene import PlanningScene

__all__ = ["rotation_error", "solve_ik"]

_DAMPING = 0.05
_POSITION_TOLERANCE = 0.004  #: metres
_ANGLE_TOLERANCE = 0.03  #: radians
_MAX_STEP = 0.25  #: radians (or metres of torso) per iteration
#: the torso moves less readily than the joints (its column is heavy): weight in the solve
_TORSO_WEIGHT = 0.5
_POSTURE_GAIN = 0.2  #: how strongly the null space pulls towards the preferred posture


def rotation_error(current: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The small rotation (axis × angle) taking ``current`` to ``target``."""
    a, b = current, target  # columns: the frames' axes; sum of a_i × b_i, written out
    error: np.ndarray = 0.5 * np.array([
        a[1, 0] * b[2, 0] - a[2, 0] * b[1, 0] + a[1, 1] * b[2, 1] - a[2, 1] * b[1, 1]
        + a[1, 2] * b[2, 2] - a[2, 2] * b[1, 2],
        a[2, 0] * b[0, 0] - a[0, 0] * b[2, 0] + a[2, 1] * b[0, 1] - a[0, 1] * b[2, 1]
        + a[2, 2] * b[0, 2] - a[0, 2] * b[2, 2],
        a[0, 0] * b[1, 0] - a[1, 0] * b[0, 0] + a[0, 1] * b[1, 1] - a[1, 1] * b[0, 1]
        + a[0, 2] * b[1, 2] - a[1, 2] * b[0, 2]])
    return error


def solve_ik(scene: PlanningScene, position: np.ndarray, rotation: np.ndarray,
             seeds: list[np.ndarray], iterations: int = 80,
             posture: np.ndarray | None = None,
             torso: float | None = None) -> np.ndarray | None:
    """A configuration that puts the grasp site at ``position`` with ``rotation``.

    Damped least squares (Levenberg-Marquardt step ``Jᵀ(JJᵀ + λ²I)⁻¹e``) from each seed in
    turn, joints clipped to their limits; the redundant freedom (8 joints for 6 numbers)
    drifts towards ``posture`` (default: the seed) in the Jacobian's null space, which
    keeps the elbow where the seed had it. ``torso`` holds the torso at that height. None
    when no seed converges.
    """
    damping = _DAMPING ** 2 * np.eye(6)
    identity = np.eye(len(scene.lower))
    weights = np.ones(len(scene.lower))
    weights[0] = _TORSO_WEIGHT if torso is None else 0.0
    for seed in seeds:
        q = np.clip(np.array(seed, dtype=float), scene.lower, scene.upper)
        if torso is not None:
            q[0] = torso
        rest = q.copy() if posture is None else posture
        for _ in range(iterations):
            scene.set(q)
            here, turn = scene.site()
            error = np.concatenate((position - here, rotation_error(turn, rotation)))
            if float(error[:3] @ error[:3]) < _POSITION_TOLERANCE ** 2 and \
                    float(error[3:] @ error[3:]) < _ANGLE_TOLERANCE ** 2:
                found: np.ndarray = q
                return found
            jac = scene.jacobian() * weights
            inverse = np.linalg.solve(jac @ jac.T + damping, jac).T
            step = inverse @ error
            step += (identity - inverse @ jac) @ (_POSTURE_GAIN * (rest - q))
            step *= weights
            largest = np.max(np.abs(step))
            if largest > _MAX_STEP:
                step *= _MAX_STEP / largest
            q = np.clip(q + step, scene.lower, scene.upper)
    return None
