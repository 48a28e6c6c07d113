"""The simulated clock: advances, observers (whole or in steps), a cancelled advance, and the
calendar time a run starts at."""

from __future__ import annotations

import re
from datetime import datetime

import pytest

from homebot.cancel import CancelToken
from homebot.clock import Clock, start_time


def test_an_observer_sees_each_advance_with_the_time_before_and_after() -> None:
    clock = Clock()
    seen: list[tuple[float, float]] = []
    clock.observe(lambda before, after: seen.append((before, after)))
    clock.advance(1.5)
    clock.advance(0.0)
    clock.advance(2.0)
    assert seen == [(0.0, 1.5), (1.5, 1.5), (1.5, 3.5)]
    assert clock.now() == 3.5


def test_observers_are_called_in_order_and_can_be_forgotten() -> None:
    clock = Clock()
    calls: list[str] = []

    def first(before: float, after: float) -> None:
        calls.append("first")

    def second(before: float, after: float) -> None:
        calls.append("second")

    clock.observe(first)
    clock.observe(second)
    clock.advance(1.0)
    clock.forget(first)
    clock.advance(1.0)
    clock.forget(first)  # forgetting twice is harmless
    assert calls == ["first", "second", "second"]


def test_an_observer_asking_for_steps_sees_a_long_advance_in_steps_that_add_up_exactly() -> None:
    clock = Clock(time=10.0)
    steps: list[tuple[float, float]] = []
    whole: list[tuple[float, float]] = []
    clock.observe(lambda before, after: steps.append((before, after)), step=0.05)
    clock.observe(lambda before, after: whole.append((before, after)))
    assert clock.advance(0.237) == 10.237  # exactly where one advance would put it
    assert len(steps) == 5  # 4 whole steps and the remainder
    assert steps[0] == (10.0, 10.05) and steps[-1][1] == 10.237
    assert all(after - before <= 0.05 + 1e-9 for before, after in steps)
    assert [before for before, _ in steps[1:]] == [after for _, after in steps[:-1]]
    assert whole == steps  # every observer sees every step


def test_a_step_barely_over_a_whole_step_is_one_step() -> None:
    clock = Clock()
    steps: list[tuple[float, float]] = []
    clock.observe(lambda before, after: steps.append((before, after)), step=0.05)
    clock.advance(0.05 + 1e-12)
    assert len(steps) == 1


def test_the_same_advances_give_the_same_observed_times() -> None:
    def observed() -> list[tuple[float, float]]:
        clock, seen = Clock(), []
        clock.observe(lambda before, after: seen.append((before, after)), step=0.1)
        for seconds in (0.35, 1.0, 0.02, 2.5):
            clock.advance(seconds)
        return seen

    assert observed() == observed()


def test_a_cancelled_advance_stops_at_the_end_of_the_step_in_which_it_was_cancelled() -> None:
    clock = Clock()
    token = CancelToken()

    def stop_at_one_second(before: float, after: float) -> None:
        if after >= 1.0:
            token.cancel("stop pressed")

    clock.observe(stop_at_one_second, step=0.25)
    assert clock.advance(10.0, cancel=token) == 1.0
    assert clock.advance(5.0, cancel=token) == 1.0  # already cancelled: no time passes
    assert clock.advance(5.0) == 6.0  # another action, not cancelled, takes its time


def test_time_cannot_run_backwards_and_steps_are_positive() -> None:
    clock = Clock()
    with pytest.raises(ValueError, match="backwards"):
        clock.advance(-1.0)
    with pytest.raises(ValueError, match="positive"):
        clock.observe(lambda before, after: None, step=0.0)


@pytest.mark.parametrize(("text", "expected"), [
    ("2026-11-29 14:30", datetime(2026, 11, 29, 14, 30)),
    ("2026-11-29T14:30:15", datetime(2026, 11, 29, 14, 30, 15)),
    (" 2026-02-28 ", datetime(2026, 2, 28)),
])
def test_a_start_is_read_as_a_person_writes_it(text: str, expected: datetime) -> None:
    assert start_time(text) == expected


@pytest.mark.parametrize("text", ["tomorrow", "2026-13-01 10:00", "29/11/2026",
                                  "2026-11-29 14:30+01:00", ""])
def test_a_start_that_is_not_a_local_date_and_time_says_how_to_write_one(text: str) -> None:
    with pytest.raises(ValueError, match=re.escape("e.g. 2026-11-29 14:30")):
        start_time(text)
