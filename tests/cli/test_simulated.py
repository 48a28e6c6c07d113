"""What ``do`` and ``run-task`` share, and ``chat`` and ``scenario`` too: the skill under way
shown while a task runs."""

from __future__ import annotations

import io

import pytest
from rich.console import Console

from homebot import progress
from homebot.app import RunSettings, build_run
from homebot.cli import main
from homebot.cli.simulated import showing_steps
from homebot.language import Vocabulary, parse_command
from homebot.progress import showing_progress
from homebot.world import World


def test_the_skill_under_way_is_shown_and_the_listener_leaves_with_the_task() -> None:
    world = World.load("apartment")
    run = build_run(RunSettings(world=world, seed=3))
    parsed = parse_command("go to the kitchen then find a drink", Vocabulary.from_world(world))
    listeners = list(run.events.listeners)
    written = io.StringIO()
    with showing_progress(Console(file=written, force_terminal=True, width=200)), \
            showing_steps(run):
        report = run.run(parsed.to_task())
    assert report.steps
    shown = written.getvalue()
    # the last skill started is on the display's last drawing, when the task ends
    last = next(event for event in reversed(run.events.events) if event.kind == "skill.start")
    assert f"carrying out the task: {last.data['skill']}(" in shown
    assert run.events.listeners == listeners


def _progress_into(monkeypatch: pytest.MonkeyPatch) -> io.StringIO:
    """The command line's progress drawn into a string, as on a terminal."""
    written = io.StringIO()
    monkeypatch.setattr(progress, "progress_console", lambda quiet=False: None if quiet else
                        Console(file=written, force_terminal=True, width=200))
    return written


def test_chat_shows_the_skill_under_way(monkeypatch: pytest.MonkeyPatch,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    written = _progress_into(monkeypatch)
    monkeypatch.setattr("sys.stdin", io.StringIO("go to the kitchen\nquit\n"))
    assert main(["chat", "--seed", "1"]) == 0
    assert "carrying out the task: navigate(to=kitchen)" in written.getvalue()


def test_a_scenario_shows_the_skill_under_way(monkeypatch: pytest.MonkeyPatch,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    written = _progress_into(monkeypatch)
    assert main(["scenario", "fetch"]) in (0, 1)
    assert "scenario fetch: " in written.getvalue()
    assert "(" in written.getvalue().split("scenario fetch: ", 1)[1]  # a skill and its call
