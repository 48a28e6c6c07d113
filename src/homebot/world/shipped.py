"""Where a world's file is: a path, or the name of a world that ships with homebot.

Apart from ``homebot.world.world`` so that finding the file imports neither YAML nor
pydantic nor shapely (``homebot.app.world_names`` reads a world's names from a cache).
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from homebot.errors import WorldError

__all__ = ["shipped_world_names", "shipped_world_path", "world_file"]


def shipped_world_names() -> list[str]:
    """Names of the worlds that ship with homebot (``apartment``, ``supermarket``...)."""
    folder = resources.files("homebot.data") / "worlds"
    return sorted(entry.name[: -len(".yaml")] for entry in folder.iterdir()
                  if entry.name.endswith(".yaml"))


def shipped_world_path(name: str) -> Path:
    """The file of a shipped world."""
    return Path(str(resources.files("homebot.data") / "worlds" / f"{name}.yaml"))


def world_file(path_or_name: str | Path) -> Path:
    """The file of ``path_or_name``: itself, or the shipped world of that name when it has
    no suffix and no such file exists.

    Raises:
        WorldError: a name that is neither a file nor a shipped world.
    """
    candidate = Path(path_or_name)
    if candidate.suffix or candidate.exists():
        return candidate
    if str(path_or_name) not in shipped_world_names():
        raise WorldError(f"no world named '{path_or_name}'; give a YAML file or one of: "
                         f"{', '.join(shipped_world_names())}")
    return shipped_world_path(str(path_or_name))
