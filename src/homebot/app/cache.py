"""Where trained models are kept between processes, and the key that says when one is stale.

Training the face cascade and enrolling a household take tens of seconds of CPU, so the
result is pickled to disk. A pickle is only as good as the code and the libraries that
made it: the key covers the source of the modules that shape it, homebot's version,
Python's, and the versions of the libraries its models are made of (scikit-learn's trees,
numpy's arrays ...), so an upgrade trains afresh instead of reading a stale model.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import os
import platform
from collections.abc import Iterable
from pathlib import Path
from types import ModuleType

import homebot

__all__ = ["CACHE_DIRECTORY_VARIABLE", "LIBRARIES", "cache_directory", "cache_key"]

CACHE_DIRECTORY_VARIABLE = "HOMEBOT_CACHE_DIR"  #: names the folder; default ~/.cache/homebot
#: distributions whose versions shape what is cached (a missing one counts as "absent")
LIBRARIES = ("numpy", "scipy", "scikit-learn", "opencv-python-headless", "opencv-python",
             "numba")


def cache_directory() -> Path:
    """Where trained models are kept: ``$HOMEBOT_CACHE_DIR``, else ``~/.cache/homebot``."""
    chosen = os.environ.get(CACHE_DIRECTORY_VARIABLE)
    return Path(chosen) if chosen else Path.home() / ".cache" / "homebot"


def cache_key(what: object, modules: Iterable[ModuleType],
              libraries: Iterable[str] = LIBRARIES) -> str:
    """A short hex key for ``what`` (its ``repr``) made by ``modules``' source with
    ``libraries`` at their installed versions: new code or a new library, new key."""
    key = hashlib.sha256(repr(what).encode())
    for module in modules:
        key.update(Path(str(module.__file__)).read_bytes())
    key.update(f"homebot {homebot.__version__}; python {platform.python_version()}".encode())
    for library in libraries:
        key.update(f"; {library} {_version(library)}".encode())
    return key.hexdigest()[:20]


def _version(distribution: str) -> str:
    try:
        return importlib.metadata.version(distribution)
    except importlib.metadata.PackageNotFoundError:
        return "absent"
