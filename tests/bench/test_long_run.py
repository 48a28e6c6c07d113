"""``bench long_run``: every task a whole fetch, the event log within its bound, a growth curve."""

from __future__ import annotations

import argparse

from homebot.bench import long_run


def _run(tasks: int, keep: int, *options: str) -> dict[str, object]:
    parser = argparse.ArgumentParser()
    long_run.add_arguments(parser)
    args = parser.parse_args(["--tasks", str(tasks), "--warm-up", "5", "--keep", str(keep),
                              *options])
    return long_run.run(args)


def test_objects_are_put_back_so_every_task_is_a_whole_fetch() -> None:
    # 60 tasks over 33 objects: left with their people, the second round has nothing to fetch
    assert _run(60, 400)["succeeded"] == 60
    assert _run(60, 400, "--no-put-back")["succeeded"] < 40


def test_the_log_holds_no_more_than_it_keeps_and_the_curve_has_ten_readings() -> None:
    figures = _run(20, 50)
    assert figures["events_recorded"] > 10 * 50  # far more recorded than kept
    assert 45 <= figures["events_in_memory"] <= 50
    curve = figures["rss_growth_curve_mb"]
    assert [done for done, _ in curve] == list(range(2, 21, 2))
