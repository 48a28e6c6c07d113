"""Imports go downward: engines and skills reach the world through the Robot port, not sim."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SOURCE = Path(__file__).resolve().parents[1] / "src" / "homebot"
ENGINES = ["knowledge", "skills", "executive", "htn", "golog", "sitlog", "inference", "language"]


def _imported(path: Path) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return names


def _imports_of(package: str, prefixes: tuple[str, ...]) -> list[str]:
    """Every import in ``homebot.<package>`` of a module under one of ``prefixes``."""
    return sorted(
        f"{path.relative_to(SOURCE)}: {name}"
        for path in (SOURCE / package).rglob("*.py")
        for name in _imported(path)
        if any(name == prefix or name.startswith(f"{prefix}.") for prefix in prefixes)
    )


@pytest.mark.parametrize("package", ENGINES)
def test_engines_never_import_the_simulator(package: str) -> None:
    assert _imports_of(package, ("homebot.sim",)) == []


@pytest.mark.parametrize("package", ["navigation", "embodied", "perception"])
def test_the_action_perception_layer_sees_the_world_only_through_the_body(package: str) -> None:
    assert _imports_of(package, ("homebot.sim",)) == []


def test_the_simulator_never_imports_the_robots_algorithms() -> None:
    algorithms = ("homebot.embodied", "homebot.perception", "homebot.navigation.localisation",
                  "homebot.navigation.likelihood", "homebot.navigation.local_planner",
                  "homebot.navigation.dwa", "homebot.navigation.navigate")
    assert _imports_of("sim", algorithms) == []
