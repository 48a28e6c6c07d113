"""A world's names (rooms, furniture, objects, people, doors), kept between processes.

Understanding a command needs only the names in the world it is said in
(``homebot.language.Vocabulary``). Loading the world to get them (YAML, pydantic, shapely
and numpy) costs tens of times more than parsing the command, so a one-shot
``homebot parse`` would be mostly start-up. The names are kept as JSON in the cache
folder (``homebot.app.cache``), under a key made of the world file's bytes and the source
of the code that reads it: an edited world, or new homebot code, reads the world afresh.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
from pathlib import Path
from typing import Any

import homebot
from homebot.app.cache import cache_directory
from homebot.errors import WorldError
from homebot.files import read_bytes_file
from homebot.language import Vocabulary
from homebot.language.vocabulary import names_in_world
from homebot.world.shipped import world_file

__all__ = ["world_names", "world_vocabulary"]

_FOLDER = "world_names"
#: the source that decides which names a world file has, and how a vocabulary is built
_CODE = (Path(homebot.__file__).parent / "world", Path(homebot.__file__).parent / "language")


def world_vocabulary(path_or_name: str | Path) -> Vocabulary:
    """The vocabulary of a world file or shipped world, from the cache when the file and
    the code are as they were (``world_names``).

    Raises:
        WorldError: the world cannot be loaded (as ``World.load`` says).
    """
    return Vocabulary.from_names(**world_names(path_or_name))


def world_names(path_or_name: str | Path) -> dict[str, Any]:
    """``Vocabulary.from_names``'s arguments for a world: read from the cache, or from the
    world itself (then kept). A cache that cannot be read or written is only slower."""
    path = world_file(path_or_name)
    text = read_bytes_file(path, WorldError, "yaml")
    cached = cache_directory() / _FOLDER / f"{_key(text)}.json"
    try:
        names: dict[str, Any] = json.loads(cached.read_text(encoding="utf-8"))
        return names
    except (OSError, ValueError):
        pass
    from homebot.world import World  # the slow part the cache saves

    names = names_in_world(World.load(path))
    try:
        cached.parent.mkdir(parents=True, exist_ok=True)
        partial = cached.with_suffix(f".{os.getpid()}.partial")
        partial.write_text(json.dumps(names), encoding="utf-8")
        partial.replace(cached)  # whole or not at all, for a process reading beside
    except OSError:
        pass
    return names


def _key(world_text: bytes) -> str:
    key = hashlib.sha256(world_text)
    for folder in _CODE:
        for source in sorted(folder.glob("*.py")):
            key.update(source.name.encode())
            key.update(source.read_bytes())
    key.update(f"homebot {homebot.__version__}; python {platform.python_version()}".encode())
    return key.hexdigest()[:24]
