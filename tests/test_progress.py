"""Progress: drawn on a terminal, silent in a pipe and under ``--json``."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import pytest
from rich.console import Console

from homebot.cli import main
from homebot.progress import progress_console, showing_progress, start, task, track

SRC = Path(__file__).resolve().parents[1] / "src"


def _terminal() -> tuple[Console, io.StringIO]:
    written = io.StringIO()
    return Console(file=written, force_terminal=True, width=100), written


def test_a_task_is_drawn_on_a_terminal_with_its_count() -> None:
    console, written = _terminal()
    with showing_progress(console), task("teaching faces", total=3) as teaching:
        teaching.advance(3)
    assert "teaching faces" in written.getvalue()
    assert "3/3" in written.getvalue()


def test_track_yields_every_item_and_counts_them() -> None:
    console, written = _terminal()
    with showing_progress(console):
        seen = list(track(["a", "b", "c", "d"], "letters"))
        again = list(track(iter(range(2)), "a second task, after the first ended"))
    assert seen == ["a", "b", "c", "d"] and again == [0, 1]
    assert "letters" in written.getvalue() and "4/4" in written.getvalue()
    # the display stopped with the first task and started again for the second
    assert "a second task, after the first ended" in written.getvalue()


def test_nested_tasks_are_drawn_together() -> None:
    console, written = _terminal()
    with showing_progress(console), task("outer", total=2) as outer:
        with task("inner"):
            pass
        outer.advance(2)
    assert "outer" in written.getvalue() and "inner" in written.getvalue()


def test_nothing_is_drawn_without_a_display() -> None:
    _, written = _terminal()
    with showing_progress(None):
        assert list(track(range(3), "quiet")) == [0, 1, 2]
        quiet = start("quiet too", total=1)
        quiet.advance()
        quiet.describe("still quiet")
        quiet.end()
    assert list(track(range(2), "outside any display")) == [0, 1]
    assert written.getvalue() == ""


def test_an_unknown_size_shows_no_count() -> None:
    console, written = _terminal()
    with showing_progress(console), task("sizeless"):
        pass
    assert "sizeless" in written.getvalue() and "/?" not in written.getvalue()


def test_no_progress_console_in_a_pipe_or_when_quiet(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("FORCE_COLOR", "1")  # colour in a CI log is still no terminal
    read, write = os.pipe()
    with os.fdopen(write, "w") as pipe, os.fdopen(read):
        monkeypatch.setattr(sys, "stderr", pipe)
        assert progress_console() is None
    assert progress_console(quiet=True) is None


def test_a_kernel_compilation_is_shown() -> None:
    numba = pytest.importorskip("numba")
    from homebot.compiled import compiled

    def kernel(x: int) -> int:
        return x + 1

    compiled(kernel)  # the first kernel decorated listens to numba's compilations
    fresh = numba.njit(kernel)  # not cached on disk: compiled on its first call
    written = io.StringIO()
    with showing_progress(Console(file=written, force_terminal=True, width=300)):
        assert fresh(1) == 2
    assert "test_a_kernel_compilation_is_shown.<locals>.kernel (the first run only" \
        in written.getvalue()
    assert "compiling " in written.getvalue()


def test_a_benchmark_under_json_and_in_a_pipe_prints_only_its_figures(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "sitlog", "--repeat", "2", "--json"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    assert main(["bench", "sitlog", "--repeat", "2"]) == 0
    assert "running Appendix A" not in capsys.readouterr().err


def _on_a_terminal(*arguments: str) -> str:
    """What ``homebot ARGUMENTS`` writes to stderr when stderr is a terminal (a pty)."""
    import pty

    controller, terminal = pty.openpty()
    environment = {**os.environ, "PYTHONPATH": str(SRC), "COLUMNS": "120"}
    environment.pop("TTY_COMPATIBLE", None)
    done = subprocess.run(
        [sys.executable, "-c", "import sys; from homebot.cli import main; sys.exit(main())",
         *arguments], stdout=subprocess.PIPE, stderr=terminal, env=environment, check=False,
        timeout=120)
    os.close(terminal)
    written = b""
    while True:
        try:
            chunk = os.read(controller, 65536)
        except OSError:  # the terminal's other end is closed: all is read
            break
        if not chunk:
            break
        written += chunk
    os.close(controller)
    assert done.returncode == 0, written
    return written.decode(errors="replace")


def test_a_benchmark_on_a_terminal_shows_its_progress_and_none_under_json() -> None:
    shown = _on_a_terminal("bench", "sitlog", "--repeat", "3")
    assert "bench sitlog" in shown and "running Appendix A" in shown and "3/3" in shown
    assert "running Appendix A" not in _on_a_terminal("bench", "sitlog", "--repeat", "3",
                                                      "--json")
