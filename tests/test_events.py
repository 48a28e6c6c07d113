"""``EventLog``: its bound holds however many events are recorded, and none is lost to a stream."""

from __future__ import annotations

import io
import json

import pytest

from homebot.events import EventLog


@pytest.mark.parametrize("keep", [1, 7, 50, 5000])
def test_the_log_never_holds_more_than_it_keeps(keep: int) -> None:
    events = EventLog(lambda: 0.0, keep=keep)
    held = []
    for number in range(3 * keep + 11):
        events.record("tick", number=number)
        held.append(len(events.events))
    assert max(held) == keep
    assert min(held[keep:]) >= keep - keep // 10  # and most of them stay
    assert events.count == 3 * keep + 11
    assert events.events[-1].data["number"] == 3 * keep + 10  # the newest are the ones kept


def test_since_counts_from_the_first_event_ever_recorded() -> None:
    events = EventLog(lambda: 0.0, keep=10)
    for number in range(35):
        events.record("tick", number=number)
    assert [event.data["number"] for event in events.since(33)] == [33, 34]
    assert events.since(0)[0].data["number"] == events.dropped


def test_a_stream_gets_every_event_the_memory_lets_go() -> None:
    stream = io.StringIO()
    events = EventLog(lambda: 1.5, keep=4, stream=stream)
    for number in range(20):
        events.record("tick", number=number)
    lines = [json.loads(line) for line in stream.getvalue().splitlines()]
    assert [line["number"] for line in lines] == list(range(20))
    assert len(events.events) <= 4
