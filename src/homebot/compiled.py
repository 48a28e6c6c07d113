"""The decorator for compiled kernels (numba, from the ``embodied`` extra): the navigation's,
the simulated laser's and the face forests' walk.

A kernel is plain Python over scalars and arrays: without numba it runs as it
is (slower), and tests run the very same code as ``kernel.py_func``. Modules
holding kernels import this one, and are themselves imported only where a
kernel is first needed, so that the symbolic fidelity never loads numba.
``cache=True`` keeps the compiled code on disk (``__pycache__``): a second
process loads it instead of compiling again. The first compiles take tens of
seconds together, so each is shown as a task (``homebot.progress``).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar, cast

from homebot import progress

__all__ = ["compiled"]

_F = TypeVar("_F", bound=Callable[..., Any])


def compiled(function: _F) -> _F:
    """``function`` compiled by numba (cached on disk) when numba is there, else as it is."""
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - the embodied extra brings numba
        return function
    _show_compilations()
    return cast(_F, njit(cache=True, nogil=True)(function))


@functools.cache  # one listener for the process: numba's events are the process's
def _show_compilations() -> None:
    """Show each compilation of a kernel (not a load from numba's cache) as a task."""
    from numba.core import event

    class Compilations(event.Listener):
        """The outermost kernel being compiled is a task; the kernels it calls, compiled
        within it, are part of it."""

        def __init__(self) -> None:
            self._nested: list[progress.Task | None] = []

        def on_start(self, happening: event.Event) -> None:
            if self._nested:
                self._nested.append(None)
                return
            kernel = happening.data["dispatcher"].py_func
            name = f"{kernel.__module__.removeprefix('homebot.')}.{kernel.__qualname__}"
            self._nested.append(progress.start(
                f"compiling {name} (the first run only: kept on disk after)"))

        def on_end(self, happening: event.Event) -> None:
            began = self._nested.pop() if self._nested else None
            if began is not None:
                began.end()

    event.register("numba:compile", Compilations())  # type: ignore[no-untyped-call]
