"""Program files that ship with homebot (``src/homebot/data/golog/*.golog``) and loading files."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from homebot.errors import GologError
from homebot.files import read_text_file
from homebot.golog.program import Procedure
from homebot.golog.syntax import parse_procedures

__all__ = ["load_procedures", "shipped_procedures", "shipped_program_names"]


def shipped_program_names() -> list[str]:
    """Names of the shipped program files (``order_cups``, ``maze``, ``rips``...)."""
    folder = resources.files("homebot.data") / "golog"
    return sorted(entry.name[: -len(".golog")] for entry in folder.iterdir()
                  if entry.name.endswith(".golog"))


def shipped_procedures(name: str) -> list[Procedure]:
    """The procedures of a shipped program file."""
    if name not in shipped_program_names():
        raise GologError(f"no shipped Golog program '{name}'; "
                         f"choose one of {', '.join(shipped_program_names())}")
    path = resources.files("homebot.data") / "golog" / f"{name}.golog"
    return parse_procedures(path.read_text(encoding="utf-8"), f"{name}.golog")


def load_procedures(path: str | Path) -> list[Procedure]:
    """The procedures of a program file; a missing file raises ``GologError``."""
    file = Path(path)
    return parse_procedures(read_text_file(file, GologError, "text", "Golog program"),
                            str(file))
