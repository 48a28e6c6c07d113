"""Sessions and the control lease on a stepped clock: issue, forget, lapse, renew, release."""

from __future__ import annotations

import math
import threading

import pytest

from homebot.errors import ConsoleError
from homebot.web.sessions import ControlLease, Sessions


class Stepped:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_a_session_is_known_by_its_secret_only_and_forgotten_when_idle_or_ended() -> None:
    clock = Stepped()
    sessions = Sessions(idle=60.0, clock=clock)
    secret, name = sessions.open()
    assert sessions.name(secret) == name and secret != name
    assert sessions.name(name) is None and sessions.name(secret[:-1]) is None
    assert sessions.name("") is None and sessions.name(None) is None
    clock.now += 59.0
    assert sessions.name(secret) == name  # a request counts as heard from
    clock.now += 59.0
    assert sessions.name(secret) == name
    clock.now += 60.5
    assert sessions.name(secret) is None and len(sessions) == 0
    other, _ = sessions.open()
    assert sessions.close(other) is not None and sessions.name(other) is None


def test_at_most_limit_sessions_live_the_longest_silent_forgotten_first() -> None:
    clock = Stepped()
    sessions = Sessions(limit=3, clock=clock)
    first, _ = sessions.open()
    second, _ = sessions.open()
    clock.now += 1
    sessions.name(first)  # heard from: the second is now the longest silent
    for _ in range(2):
        sessions.open()
    assert len(sessions) == 3
    assert sessions.name(second) is None and sessions.name(first) is not None


def test_the_lease_lapses_without_renewal_and_only_its_holder_renews_or_releases() -> None:
    clock = Stepped()
    lease = ControlLease(10.0, clock=clock)
    lease.take("ann")
    with pytest.raises(ConsoleError, match="another operator"):
        lease.take("bob")
    assert not lease.renew("bob")
    lease.release("bob")
    assert lease.holder == "ann"
    clock.now += 9.0
    assert lease.renew("ann") and lease.left() == 10.0
    clock.now += 10.0
    assert lease.holder == "ann"
    clock.now += 0.01
    assert lease.holder is None and lease.left() == 0.0 and not lease.renew("ann")
    lease.take("bob")
    assert lease.holder == "bob"


@pytest.mark.parametrize("seconds", [0.0, -1.0, math.nan])
def test_a_lease_of_no_time_is_refused(seconds: float) -> None:
    with pytest.raises(ConsoleError, match="above 0"):
        ControlLease(seconds)


def test_a_flood_of_new_sessions_never_forgets_the_one_named_to_keep() -> None:
    clock = Stepped()
    sessions = Sessions(limit=3, clock=clock)
    holder, name = sessions.open()
    for _ in range(50):
        clock.now += 1
        sessions.open(keep=name)
    assert len(sessions) == 3 and sessions.name(holder) == name


def test_the_heartbeat_never_waits_for_the_robot() -> None:
    """While the robot thinks (the console's lock held), a page still renews, takes and
    gives back control: a renewal that waited for it could find the lease lapsed."""
    pytest.importorskip("fastapi")
    from homebot.web import Console, ConsoleSettings
    from homebot.world import World

    clock = Stepped()
    home = Console(ConsoleSettings(world=World.load("apartment"), token="t", speed=0.0),
                   lease_clock=clock)
    home.take_control("ann")
    thinking, done = threading.Event(), threading.Event()

    def think() -> None:
        with home.lock:
            thinking.set()
            done.wait(30.0)

    robot = threading.Thread(target=think)
    robot.start()
    assert thinking.wait(30.0)
    answers: list[object] = []

    def page() -> None:
        answers.append(home.renew_control("ann"))
        home.release_control("ann")
        answers.append(home.controller)
        home.take_control("bob")
        answers.append(home.controller)

    heartbeat = threading.Thread(target=page)
    heartbeat.start()
    heartbeat.join(10.0)
    answered = list(answers)  # while the robot still thinks
    done.set()
    robot.join()
    heartbeat.join()
    assert answered == [True, None, "bob"]
