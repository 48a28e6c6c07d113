"""Task-space compliance: per-axis, per-direction yielding, and the Jacobian-transpose mapping."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.manipulation.compliance import (
    ArmReading,
    AxisCompliance,
    Compliance,
    ComplianceController,
    displacement,
    joint_torques,
    task_wrench,
)


def test_a_compliant_direction_yields_and_the_other_holds() -> None:
    axis = AxisCompliance(stiffness=1500.0, damping=0.0, max_force=40.0, min_force=2.0,
                          span=0.1, positive=True)
    # Upward (positive) it gives: a small displacement is held with little force ...
    assert axis.limit(0.01) == pytest.approx(2.0 + 0.1 * 38.0)
    # ... and full force only a span away; downward it holds with everything it has.
    assert axis.limit(0.1) == pytest.approx(40.0)
    assert axis.limit(-0.01) == 40.0
    assert axis.rest_shift(21.0) == pytest.approx(0.05)
    assert axis.rest_shift(-21.0) == 0.0


def test_the_wrench_pushes_back_within_the_limits() -> None:
    compliance = Compliance().compliant_in("z", negative=False)
    shift = np.array([0.01, 0.0, 0.05, 0.0, 0.0, 0.0])
    wrench = task_wrench(compliance, shift, np.zeros(6))
    assert wrench[0] == pytest.approx(-15.0)  # stiff in x: 1500 N/m × 1 cm
    z = compliance.axes[2]
    assert wrench[2] == pytest.approx(-z.limit(0.05))  # compliant upwards: the limit binds
    assert abs(wrench[2]) < abs(compliance.axes[2].stiffness * 0.05)
    damped = task_wrench(compliance, np.zeros(6), np.array([0.1, 0, 0, 0, 0, 0]))
    assert damped[0] == pytest.approx(-compliance.axes[0].damping * 0.1)


def test_displacement_reads_position_and_rotation() -> None:
    angle = 0.2
    rotation = np.array([[np.cos(angle), -np.sin(angle), 0.0],
                         [np.sin(angle), np.cos(angle), 0.0], [0.0, 0.0, 1.0]])
    shift = displacement(np.array([1.0, 0.0, 0.5]), rotation, np.array([0.9, 0.0, 0.5]),
                         np.eye(3))
    np.testing.assert_allclose(shift, [0.1, 0.0, 0.0, 0.0, 0.0, angle], atol=1e-12)


def test_torques_are_the_jacobian_transpose_and_the_null_space_leaves_the_hand_alone() -> None:
    rng = np.random.default_rng(3)
    jacobian = rng.normal(size=(6, 7))
    state = ArmReading(q=np.zeros(7), qd=np.zeros(7), hand_position=np.zeros(3),
                       hand_rotation=np.eye(3), jacobian=jacobian, gravity=np.ones(7))
    wrench = rng.normal(size=6)
    compliance = Compliance()
    plain = joint_torques(state, wrench, compliance)
    np.testing.assert_allclose(plain, jacobian.T @ wrench + 1.0)
    rest = rng.normal(size=7)
    with_posture = joint_torques(state, wrench, compliance, rest)
    # The posture torque is in the null space: it produces no force at the hand.
    posture = with_posture - plain
    assert np.linalg.norm(posture) > 1e-3
    np.testing.assert_allclose(np.linalg.pinv(jacobian.T) @ posture, np.zeros(6), atol=1e-9)


def test_the_controller_keeps_the_last_shift_for_behaviours() -> None:
    controller = ComplianceController(Compliance(), np.zeros(3), np.eye(3))
    state = ArmReading(q=np.zeros(6), qd=np.zeros(6), hand_position=np.array([0.0, 0.02, 0.0]),
                       hand_rotation=np.eye(3), jacobian=np.eye(6), gravity=np.zeros(6))
    tau = controller.torques(state)
    assert controller.shift[1] == pytest.approx(0.02)
    assert tau[1] == pytest.approx(-30.0)


def test_bad_settings_are_refused() -> None:
    with pytest.raises(ValueError, match="span"):
        AxisCompliance(stiffness=1.0, damping=1.0, max_force=1.0, span=0.0)
    with pytest.raises(ValueError, match="unknown task axis"):
        Compliance().with_axes(w={"positive": True})
