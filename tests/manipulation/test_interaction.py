"""The interaction behaviours as state machines, on hand-made readings (no physics)."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.manipulation.interaction import (
    CarryPhase,
    CarryTable,
    DoorMotion,
    DoorPhase,
    GuidedByHand,
    Handover,
    Receive,
    ReceivePhase,
)
from homebot.manipulation.tools import PourPhase, Tool, WateringMotion, turn

HAND = np.array([0.7, 0.0, 1.0])


def _shift(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    return np.array([x, y, z, 0.0, 0.0, 0.0])


def test_handover_lets_go_for_a_pull_and_never_for_a_bump() -> None:
    handover = Handover(HAND, np.eye(3), threshold=10.0)
    forward = handover.compliance.axes[0]
    bump = forward.rest_shift(6.0)  # where a 6 N push leaves the hand
    for tick in range(50):
        assert handover.update(tick * 0.01, _shift(x=bump)).gripper_closed
    assert handover.released_at is None
    pull = forward.rest_shift(10.0)
    handover.update(0.5, _shift(x=pull))
    command = handover.update(0.51, _shift(x=pull))
    assert not command.gripper_closed and handover.released_at == pytest.approx(0.51)


def test_receive_closes_on_a_touch_and_holds_what_has_weight() -> None:
    receive = Receive(HAND, np.eye(3), close_time=0.5)
    rest = np.array([0.0, 0.0, -2.0])
    assert not receive.update(0.0, rest, 0.14).gripper_closed
    assert receive.update(0.1, rest + np.array([-3.0, 0.0, 0.0]), 0.14).gripper_closed
    assert receive.phase is ReceivePhase.CLOSING
    receive.update(0.7, rest + np.array([0.0, 0.0, -4.0]), 0.06)
    assert receive.phase is ReceivePhase.HOLDING
    empty = Receive(HAND, np.eye(3), close_time=0.5)
    empty.update(0.0, rest, 0.14)
    empty.update(0.1, rest + np.array([-3.0, 0.0, 0.0]), 0.14)
    empty.update(0.7, rest, 0.0)
    assert empty.phase is ReceivePhase.EMPTY


def test_guided_by_hand_drives_where_it_is_led_and_stands_when_untouched() -> None:
    guided = GuidedByHand(HAND, np.eye(3))
    assert guided.update(_shift()).base.is_zero()
    ahead = guided.update(_shift(x=0.05)).base
    assert ahead.vx > 0.2 and ahead.vy == pytest.approx(0.0)
    left = guided.update(_shift(y=0.05)).base
    assert left.vy > 0.2
    pushed = guided.update(_shift(x=-0.05)).base
    assert pushed.vx < 0.0  # pushed back: it gives way


def test_guided_by_hand_follows_the_hands_trail_not_the_shortcut() -> None:
    guided = GuidedByHand(HAND, np.eye(3), lookahead=0.3)
    pose = (0.0, 0.0, 0.0)
    guided.update(_shift(x=0.05), pose)  # the trail runs straight ahead to the hand
    # The hand is pulled to the left now; the base still drives along its trail first.
    twist = guided.update(_shift(x=0.05, y=0.05), pose).base
    assert twist.vx > abs(twist.vy) and twist.wz > 0.0


def test_carry_table_waits_lifts_levels_and_lowers() -> None:
    carry = CarryTable(HAND, np.eye(3), length=1.2, torso=0.1)
    dt = 0.01
    carry.update(dt, _shift(), 0.01)
    assert carry.phase is CarryPhase.WAITING
    command = carry.update(dt, _shift(), 0.05)
    assert carry.phase is CarryPhase.CARRYING and command.hand_position[2] > HAND[2]
    for _ in range(100):
        command = carry.update(dt, _shift(), 0.05)
    assert carry.target[2] > HAND[2] + 0.05
    # The torso carries the height change; the arm keeps its posture.
    assert command.torso == pytest.approx(min(0.5, 0.1 + carry.target[2] - HAND[2]))
    # A wobble below level while the person's end stands still is not lowering.
    for _ in range(30):
        carry.update(dt, _shift(), 0.0)
    for _ in range(5):
        carry.update(dt, _shift(), -0.03)
    assert carry.phase is CarryPhase.CARRYING
    for _ in range(30):
        carry.update(dt, _shift(), -0.05)
        if carry.phase is CarryPhase.LOWERING:
            break
    assert carry.phase is CarryPhase.LOWERING
    for _ in range(1000):  # the robot's end comes down, the table levels
        carry.update(dt, _shift(), -0.05 if carry.target[2] > HAND[2] + 0.02 else 0.0)
    assert carry.phase is CarryPhase.LOWERING
    carry.update(dt, _shift(z=0.03), 0.0)  # the floor holds the hand up
    assert carry.phase is CarryPhase.DONE


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_door_motion_pulls_the_handle_round_the_hinge_towards_the_robot(side: float) -> None:
    # The hinge 0.7 m to one side of the handle; the hand is at the handle, 0.7 m ahead.
    hand = np.array([0.7, 0.0, 0.95])
    hinge = (0.78, side * 0.7)
    door = DoorMotion(hinge, (0.0, 0.0, 0.0), hand, np.eye(3))
    command = door.update(0.01, (0.0, 0.0, 0.0), hand)
    step = command.hand_position - hand
    assert step[0] < 0.0 and abs(step[1]) < abs(step[0])  # towards the robot
    assert command.base.vx < 0.0  # and the base backs away with it
    # The door turns about its hinge: the handle faces round towards the hinge's side.
    yaw = np.arctan2(command.hand_rotation[1, 0], command.hand_rotation[0, 0])
    assert np.sign(yaw) == -side
    # Come round 83 degrees, the door is open; pushed back to where the hand stops, shut.
    shut = np.array([0.78, 0.0, 0.95])  # the handle in the door's plane: against the frame
    turned = np.array([hinge[0] - 0.7, hinge[1], 0.95])
    door.update(0.01, (0.0, 0.0, 0.0), turned)
    assert door.phase is DoorPhase.OPEN and door.angle > 1.2
    door.close()
    for _ in range(40):
        command = door.update(0.01, (0.0, 0.0, 0.0), shut)
    assert door.phase is DoorPhase.CLOSED and command.base.vx == 0.0


def test_the_pouring_motion_keeps_the_spout_over_the_pot_while_it_tips() -> None:
    tool = Tool("can", (0.0, 0.21, -0.015), axis=(-1.0, 0.0, 0.0))
    pot = np.array([0.6, 0.21, 0.66])
    motion = WateringMotion(tool, np.array([0.6, 0.0, 0.95]), np.eye(3), pot)
    tips = []
    while motion.phase is not PourPhase.DONE:
        position, rotation = motion.update(0.05)
        tips.append(position + rotation @ np.array(tool.tip))
        if motion.phase is PourPhase.POURING:
            # The spout's tip points down once tipped (rolled about the hand's x axis).
            assert (rotation @ np.array([0.0, 1.0, 0.0]))[2] < -0.5
    over = [tip for tip in tips[-40:]]
    for tip in over:
        np.testing.assert_allclose(tip, pot + np.array([0.0, 0.0, 0.1]), atol=1e-9)
    np.testing.assert_allclose(turn((0.0, 0.0, 1.0), np.pi / 2) @ [1.0, 0.0, 0.0],
                               [0.0, 1.0, 0.0], atol=1e-12)
