"""The progress display itself, on ``rich``: imported only when progress is shown
(``homebot.progress``), so a command in a pipe or under ``--json`` never loads rich."""

from __future__ import annotations

import sys
import threading

from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    SpinnerColumn,
    TaskID,
    TextColumn,
    TimeElapsedColumn,
)
from rich.progress import Task as RichTask
from rich.text import Text

__all__ = ["Display"]


class _Count(MofNCompleteColumn):
    """"3/10"; nothing for a task whose size is unknown (rather than "3/?")."""

    def render(self, task: RichTask) -> Text:
        return super().render(task) if task.total is not None else Text("")


class Display:
    """A ``rich`` progress display that is live while at least one task is under way."""

    def __init__(self, console: Console) -> None:
        # stdout's lines are drawn above the bars only when stdout is that terminal too:
        # otherwise they would leave a redirected stdout for the terminal
        self.progress = Progress(
            SpinnerColumn(), TextColumn("{task.description}"), BarColumn(),
            _Count(), TimeElapsedColumn(), console=console, transient=True,
            redirect_stdout=sys.stdout.isatty(), redirect_stderr=False)
        self._under_way = 0
        self._lock = threading.Lock()

    # A task is drawn when it is added and when it ends, however short: the display
    # starts (and stops) with it drawn, or is redrawn.
    def add(self, description: str, total: float | None) -> TaskID:
        with self._lock:
            task_id = self.progress.add_task(description, total=total)
            self._under_way += 1
            if self._under_way == 1:
                self.progress.start()
            else:
                self.progress.refresh()
            return task_id

    def remove(self, task_id: TaskID) -> None:
        with self._lock:
            self._under_way -= 1
            if self._under_way:
                self.progress.refresh()
            else:
                self.progress.stop()
            self.progress.remove_task(task_id)
