"""The people's forces: pulses, seeded handover trials, walked trajectories, a gripping hand."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.sim.forces import ForceProfile, ForcePulse, GrippingHand, Trajectory, handover_trial


def test_a_pulse_ramps_holds_and_ends() -> None:
    pulse = ForcePulse(1.0, 2.0, (10.0, 0.0, 0.0), ramp=0.2)
    assert pulse.at(0.9)[0] == 0.0 and pulse.at(1.1)[0] == pytest.approx(5.0)
    assert pulse.at(1.5)[0] == pytest.approx(10.0) and pulse.at(2.0)[0] == 0.0
    profile = ForceProfile((pulse, ForcePulse(3.0, 3.5, (0.0, 4.0, 0.0))))
    assert profile.first_above(8.0) == pytest.approx(1.161, abs=0.002)
    assert profile.first_above(20.0) is None
    with pytest.raises(ValueError):
        ForcePulse(2.0, 1.0, (1.0, 0.0, 0.0))


def test_handover_trials_are_seeded_and_keep_bumps_below_the_threshold() -> None:
    pulls = 0
    for k in range(40):
        trial = handover_trial(np.random.default_rng([7, k]), threshold=10.0)
        again = handover_trial(np.random.default_rng([7, k]), threshold=10.0)
        assert trial == again
        bumps = trial.profile.pulses[:trial.bumps]
        assert all(p.magnitude < 10.0 for p in bumps)
        if trial.pull_above is None:
            assert trial.profile.first_above(10.0) is None
        else:
            pulls += 1
            assert all(p.end < trial.pull_above for p in bumps)
    assert 0 < pulls < 40
    never = handover_trial(np.random.default_rng(1), threshold=10.0, pull=False)
    assert never.pull_above is None


def test_a_gripping_hand_pulls_towards_its_walk() -> None:
    walk = Trajectory.walked([(0.0, 0.0, 1.0), (2.0, 0.0, 1.0)], speed=0.5, start=1.0)
    assert walk.end == pytest.approx(5.0)
    np.testing.assert_allclose(walk.at(3.0), [1.0, 0.0, 1.0])
    np.testing.assert_allclose(walk.velocity(3.0), [0.5, 0.0, 0.0])
    hand = GrippingHand(walk, stiffness=100.0, damping=0.0, max_force=20.0)
    np.testing.assert_allclose(hand.force(3.0, np.array([0.9, 0.0, 1.0]), np.zeros(3)),
                               [10.0, 0.0, 0.0])
    far = hand.force(3.0, np.array([0.0, 0.0, 1.0]), np.zeros(3))
    assert np.linalg.norm(far) == pytest.approx(20.0)  # capped
