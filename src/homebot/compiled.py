"""The decorator for compiled kernels (numba, from the ``embodied`` extra): the navigation's,
the simulated laser's and the face forests' walk.

A kernel is plain Python over scalars and arrays: without numba it runs as it
is (slower), and tests run the very same code as ``kernel.py_func``. Modules
holding kernels import this one, and are themselves imported only where a
kernel is first needed, so that the symbolic fidelity never loads numba.
``cache=True`` keeps the compiled code on disk (``__pycache__``): a second
process loads it instead of compiling again.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

__all__ = ["compiled"]

_F = TypeVar("_F", bound=Callable[..., Any])


def compiled(function: _F) -> _F:
    """``function`` compiled by numba (cached on disk) when numba is there, else as it is."""
    try:
        from numba import njit
    except ImportError:  # pragma: no cover - the embodied extra brings numba
        return function
    return cast(_F, njit(cache=True, nogil=True)(function))
