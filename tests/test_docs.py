"""The README and the documentation site name only code that exists: every ``homebot.X``
written in code style, and every ``X.Y`` whose first part is a homebot package or module,
resolves to a module, or to an attribute of one.

Packages move; a page that still names the old place misleads a newcomer, and the strict site
build (``make docs``) checks links, not prose. This test reads the prose.
"""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
# The benchmark log is history: it names code as it was.
HISTORY = {"benchmark-log.md"}
PACKAGES = sorted(path.stem for path in (ROOT / "src" / "homebot").iterdir()
                  if (path / "__init__.py").exists() or path.suffix == ".py")
# Dotted names in code style that start like a package but are not code.
NOT_CODE = {
    # the world file's fields (robot: {speed: ..., laser: ...})
    "robot.speed", "robot.angular_speed", "robot.drive", "robot.laser", "robot.arm",
    # event kinds in the event log
    "robot.lost", "sim.speech", "sim.final", "task.end",
    # file names
    "world.yaml", "task.yaml",
}


def named_code() -> dict[str, list[str]]:
    """Every dotted ``homebot.X`` in code style, with the pages that name it."""
    names: dict[str, list[str]] = {}
    for page in PAGES:
        if page.name in HISTORY:
            continue
        text = page.read_text(encoding="utf-8")
        found = re.findall(r"`(homebot(?:\.\w+)+)", text)
        found += ["homebot." + name for name in re.findall(
            r"`((?:" + "|".join(PACKAGES) + r")(?:\.\w+)+)", text) if name not in NOT_CODE]
        for name in found:
            pages = names.setdefault(name, [])
            if page.name not in pages:
                pages.append(page.name)
    return names


NAMED = named_code()


def resolve(dotted: str) -> bool:
    """Whether ``dotted`` is a module of homebot or an attribute of one."""
    parts = dotted.split(".")
    for split in range(len(parts), 0, -1):
        module_name = ".".join(parts[:split])
        try:
            found: object = importlib.import_module(module_name)
        except ModuleNotFoundError as missing:
            if missing.name is not None and not missing.name.startswith("homebot"):
                pytest.skip(f"{module_name} needs {missing.name}, an optional extra")
            continue
        for attribute in parts[split:]:
            if not hasattr(found, attribute):
                return False
            found = getattr(found, attribute)
        return True
    return False


def test_the_pages_name_code() -> None:
    assert len(NAMED) > 20


@pytest.mark.parametrize("dotted", sorted(NAMED))
def test_named_code_exists(dotted: str) -> None:
    assert resolve(dotted), f"{', '.join(NAMED[dotted])} name {dotted}, which does not exist"
