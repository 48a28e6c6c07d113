"""The console's controls on the embodied robot: teleop with obstacle slowing, e-stop, grasp."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("cv2")

from homebot.app import Fidelity
from homebot.bench.console import estop_trials
from homebot.errors import ConsoleError
from homebot.web import Console, ConsoleSettings
from homebot.world import World


@pytest.fixture(scope="module")
def apartment() -> World:
    return World.load("apartment")


def _embodied(world: World) -> Console:
    return Console(ConsoleSettings(world=world, token="test-token", fidelity=Fidelity.EMBODIED,
                                   speed=0.0), lease_clock=_FROZEN)


def _FROZEN() -> float:
    """The control lease's clock in these tests: it never moves, so control never lapses."""
    return 0.0


def test_a_keyboard_drive_into_the_kitchen_slows_before_what_is_ahead(
        apartment: World) -> None:
    home = _embodied(apartment)  # no worker: the test ticks the body itself
    home.take_control("ann")
    for _ in range(200):  # turn to face east (the kitchen arch)
        if abs(home.sim.robot_pose[2]) < 0.05:
            break
        home.drive("ann", 0.0, -1.0 if home.sim.robot_pose[2] > 0 else 1.0)
        home.step_body()
    start = home.sim.robot_pose
    samples: list[tuple[float, float]] = []  # (nearest return ahead, speed)
    still = 0
    for _ in range(1500):  # the arrow key held: full speed asked for
        home.drive("ann", 10.0, 0.0)
        ahead = home.nearest_ahead()
        home.step_body()
        speed = home.body.odometry().twist.vx
        samples.append((ahead, speed))
        still = still + 1 if speed < 0.01 else 0
        if still > 20:
            break
    end = home.sim.robot_pose
    cap = home.settings.max_linear
    assert math.dist(start[:2], end[:2]) > 2.0
    assert apartment.room_at(*end[:2]) == "kitchen"  # from the entrance into the kitchen
    assert max(speed for _, speed in samples) <= cap + 1e-9
    assert any(speed > 0.9 * cap for _, speed in samples)  # free floor: (near) the cap
    near = [speed for ahead, speed in samples if ahead < 0.8]
    assert near and max(near) < 0.75 * cap  # near an obstacle: well below the cap
    assert home.sim.collisions == []  # slowed to a stop, touched nothing
    assert still > 20  # it came to rest in front of the obstacle


def test_a_drive_without_control_or_during_a_stop_is_refused(apartment: World) -> None:
    home = _embodied(apartment)
    with pytest.raises(ConsoleError, match="take control"):
        home.drive("bob", 0.2, 0.0)
    home.take_control("ann")
    with pytest.raises(ConsoleError, match="another operator"):
        home.take_control("bob")
    home.emergency_stop()
    with pytest.raises(ConsoleError, match="emergency stop"):
        home.drive("ann", 0.2, 0.0)
    home.release_stop("ann")
    home.drive("ann", 0.2, 0.0)


@pytest.mark.parametrize("kind", ["navigation", "follow"])
def test_the_emergency_stop_stands_the_base_within_one_tick(apartment: World, kind: str) -> None:
    trials = estop_trials(apartment, kind, 2, seed=3)
    assert [trial.ticks for trial in trials] == [1, 1]
    assert all(trial.passed for trial in trials)  # and it did not move after the press


def test_a_skill_level_grasp_of_a_clicked_object(apartment: World) -> None:
    # symbolic (fast); the browser test clicks the object in the page
    home = Console(ConsoleSettings(world=apartment, token="test-token", speed=0.0),
                   lease_clock=_FROZEN)
    home.start()
    try:
        home.take_control("ann")
        target = sorted(home.sim.object_location)[0]
        home.run_steps("ann", [{"skill": "pick", "object": target}])
        assert home.wait_idle(120.0)
        with home.lock:
            assert target in home.sim.hands.values()  # ground truth: in the robot's hand
            assert home.steps.steps[-1]["status"] == "verified"
    finally:
        home.close()


def test_the_stop_cancels_a_symbolic_drive_at_the_next_step_of_the_clock(
        apartment: World) -> None:
    home = Console(ConsoleSettings(world=apartment, token="test-token", speed=0.0),
                   lease_clock=_FROZEN)
    assert "advance" not in vars(home.sim.clock)  # the console observes the clock
    pressed: list[float] = []

    def press(tick: int) -> None:  # 100 steps (5 s) into the drive to the bedroom
        if not pressed and home.steps.current >= 0 and \
                home.steps.steps[home.steps.current]["status"] == "running":
            pressed.append(home.sim.clock.now())
        elif pressed and len(pressed) == 1 and home.sim.clock.now() >= pressed[0] + 5.0:
            pressed.append(home.sim.clock.now())
            home.emergency_stop()

    home.tick_hooks.append(press)
    start = home.sim.robot_pose
    home.start()
    try:
        home.take_control("ann")
        home.run_steps("ann", [{"skill": "navigate", "to": "bedroom"}])
        assert home.wait_idle(120.0)
        with home.lock:
            assert len(pressed) == 2
            assert home.sim.robot_pose == start  # the symbolic robot stood where it was
            assert home.steps.steps[0]["status"] == "stopped" and home.steps.outcome == "stopped"
            assert home.steps.ended is False and home.steps.reason == "emergency stop"
            assert list(home.speech)[-1] == "All right, I stopped."
            preempted = list(home.sim.events.of_kind("console.preempted"))
            assert [event.data["reason"] for event in preempted] == ["emergency stop"]
            ended = next(home.sim.events.of_kind("task.end"))
            assert ended.data == {"success": False, "reason": "emergency stop"}
            stopped = [e for e in home.sim.events.of_kind("skill.status")
                       if e.data["error"] == "cancelled"]
            assert stopped and stopped[0].time == pressed[1]  # at the step of the press
    finally:
        home.close()


def test_a_fault_inside_a_task_ends_it_in_the_log_and_the_worker_goes_on(
        apartment: World) -> None:
    home = Console(ConsoleSettings(world=apartment, token="test-token", speed=0.0),
                   lease_clock=_FROZEN)
    faults: list[int] = []

    def broken(tick: int) -> None:  # a bug in an observer, 20 steps into the first task
        if not faults and home.steps.current >= 0 and tick > 20:
            faults.append(tick)
            raise ValueError("an observer's bug")

    home.tick_hooks.append(broken)
    home.start()
    try:
        home.take_control("ann")
        home.run_steps("ann", [{"skill": "navigate", "to": "bedroom"}])
        assert home.wait_idle(120.0)
        with home.lock:
            errors = [e.data["error"] for e in home.sim.events.of_kind("console.error")]
            assert errors == ["ValueError: an observer's bug"]
            ended = list(home.sim.events.of_kind("task.end"))
            assert [e.data["success"] for e in ended] == [False]
            assert home.steps.outcome == "failed"
            assert all(step["status"] != "running" for step in home.steps.steps)
        # the worker is alive: the next task runs to its end
        home.run_steps("ann", [{"skill": "navigate", "to": "kitchen"}])
        assert home.wait_idle(120.0)
        with home.lock:
            assert home.steps.outcome == "done"
            assert apartment.room_at(*home.sim.robot_pose[:2]) == "kitchen"
    finally:
        home.close()


def test_going_on_again_and_again_keeps_one_go_on_in_the_description(
        apartment: World) -> None:
    """Each "go on" names the task it goes on with once: the description does not grow
    with every press (it did, "go on: go on: ...", kept in every task.start event)."""
    home = Console(ConsoleSettings(world=apartment, token="test-token", speed=0.0),
                   lease_clock=_FROZEN)
    home.start()
    try:
        home.take_control("ann")
        home.run_steps("ann", [{"skill": "say"}], "say something")  # nothing to say: fails
        assert home.wait_idle(60.0) and home.failed_at == 0
        for _ in range(3):
            assert home.resume("ann").description == "go on: say something"
            assert home.wait_idle(60.0) and home.failed_at == 0
        with home.lock:
            started = [e.data["description"] for e in home.sim.events.of_kind("task.start")]
        assert started == ["say something"] + ["go on: say something"] * 3
    finally:
        home.close()
