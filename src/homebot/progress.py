"""Progress on work that takes seconds: a bar on the terminal, nothing anywhere else.

Code at any layer says what it is doing with ``task`` or ``track``. Whether anyone sees it
is decided once, by the command line, with ``showing_progress``: a ``rich.progress`` display
on stderr when stderr is a terminal and the output is not ``--json``; silence in a pipe, in
tests and in scripts. The display is held in a context variable for the ``with`` block
that shows it, rather than passed down: progress is for the eyes only (it never changes
what runs), and a reporter argument on every function between the command line and a
training loop would widen every layer's interface for it.

The display is live only while some task is under way, so the text a command prints
between tasks (narration, figures, a prompt) is left as it is, and a finished task's bar
disappears.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator, Sized
from contextlib import contextmanager
from contextvars import ContextVar
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:  # rich is imported only where progress is shown
    from rich.console import Console
    from rich.progress import TaskID

    from homebot.progress_display import Display

__all__ = ["Task", "progress_console", "showing_progress", "start", "task", "track"]

_T = TypeVar("_T")


_display: ContextVar[Display | None] = ContextVar("homebot_progress_display", default=None)


class Task:
    """One piece of work on the display (or on none, when progress is not shown)."""

    def __init__(self, display: Display | None, task_id: TaskID | None) -> None:
        self._display = display
        self._task_id = task_id

    def advance(self, amount: float = 1.0) -> None:
        """``amount`` more of the task's total is done."""
        if self._display is not None and self._task_id is not None:
            self._display.progress.advance(self._task_id, amount)

    def describe(self, description: str) -> None:
        """Say what the task is doing now."""
        if self._display is not None and self._task_id is not None:
            self._display.progress.update(self._task_id, description=description)

    def end(self) -> None:
        """The task is over: its bar disappears (again: nothing)."""
        if self._display is not None and self._task_id is not None:
            self._display.remove(self._task_id)
            self._task_id = None


def start(description: str, total: float | None = None) -> Task:
    """Begin a task of ``total`` steps (None: unknown, a pulsing bar); ``end`` it after."""
    display = _display.get()
    if display is None:
        return Task(None, None)
    return Task(display, display.add(description, total))


@contextmanager
def task(description: str, total: float | None = None) -> Iterator[Task]:
    """A task for the ``with`` block: ``advance`` it as its steps are done."""
    began = start(description, total)
    try:
        yield began
    finally:
        began.end()


def track(items: Iterable[_T], description: str, total: float | None = None) -> Iterator[_T]:
    """``items`` one by one, advancing a task as each is done (``total``: their number,
    when ``items`` has no length)."""
    if total is None and isinstance(items, Sized):
        total = len(items)
    with task(description, total) as under_way:
        for item in items:
            yield item
            under_way.advance()


def progress_console(*, quiet: bool = False) -> Console | None:
    """Where progress is shown: stderr, when it is a terminal and not ``quiet`` (``--json``).

    A terminal is a real one (``isatty``): ``FORCE_COLOR`` in a CI log or a test's captured
    stderr draws no bars. ``TTY_COMPATIBLE=0`` and ``TERM=dumb`` turn them off too.
    """
    if quiet:
        return None
    try:
        terminal = sys.stderr.isatty()
    except (AttributeError, ValueError):  # no stream, or a closed one
        terminal = False
    if not terminal:
        return None
    from rich.console import Console

    console = Console(stderr=True)
    return console if console.is_terminal and not console.is_dumb_terminal else None


@contextmanager
def showing_progress(console: Console | None) -> Iterator[None]:
    """Show the tasks begun in the ``with`` block on ``console`` (None: show nothing)."""
    display: Display | None = None
    if console is not None:
        from homebot.progress_display import Display

        display = Display(console)
    token = _display.set(display)
    try:
        yield
    finally:
        _display.reset(token)
        if display is not None:
            display.progress.stop()  # a task left open (an exception) takes no bar with it
