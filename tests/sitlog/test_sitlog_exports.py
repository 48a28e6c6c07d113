"""``homebot.sitlog``'s ``__all__`` lists exactly what the package exposes."""

from __future__ import annotations

import importlib
import types

import pytest


@pytest.mark.parametrize("name", ["homebot.sitlog", "homebot.sitlog.functions"])
def test_all_lists_exactly_the_public_names(name: str) -> None:
    package = importlib.import_module(name)
    public = {attribute for attribute, value in vars(package).items()
              if not attribute.startswith("_") and not isinstance(value, types.ModuleType)
              and attribute != "annotations"}
    assert set(package.__all__) == public


def test_sitlog_never_imports_the_simulator_or_the_interfaces() -> None:
    import ast
    from pathlib import Path

    import homebot.sitlog

    forbidden = ("homebot.sim", "homebot.cli", "homebot.scenarios", "homebot.web")
    root = Path(homebot.sitlog.__file__).parent
    for path in root.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [alias.name for alias in node.names] if isinstance(node, ast.Import) else (
                [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            for name in names:
                assert not name.startswith(forbidden), f"{path.name} imports {name}"
