"""``homebot.space`` is a knowledge-layer package: it imports the world, the ground, itself."""

from __future__ import annotations

import ast
from pathlib import Path

SPACE = Path(__file__).resolve().parents[2] / "src" / "homebot" / "space"
ALLOWED = ("homebot.space", "homebot.world", "homebot.geometry", "homebot.errors", "homebot.text",
           "homebot.lazy")


def test_space_imports_only_the_world_and_itself() -> None:
    imported = set()
    for path in SPACE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.module:
                imported.add(node.module)
            elif isinstance(node, ast.Import):
                imported.update(alias.name for alias in node.names)
    homebot = {name for name in imported if name.startswith("homebot")}
    assert homebot, "the check reads the package's imports"
    assert sorted(name for name in homebot if not name.startswith(ALLOWED)) == []
