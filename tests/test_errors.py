"""``homebot.errors`` holds every error a person can cause, and its docstring draws them all."""

from __future__ import annotations

import ast
import inspect
import re
from pathlib import Path

import homebot.errors as errors

SOURCE = Path(__file__).resolve().parents[1] / "src" / "homebot"


def _error_classes() -> dict[str, type]:
    return {name: value for name, value in vars(errors).items()
            if inspect.isclass(value) and issubclass(value, errors.HomebotError)}


def test_the_drawn_hierarchy_lists_every_error_under_its_parent() -> None:
    drawing = (errors.__doc__ or "").split("Hierarchy::")[1].split("\n\n")[1]
    drawn: dict[str, str | None] = {}
    parents: list[tuple[int, str]] = []
    for line in drawing.splitlines():
        match = re.match(r"^(\s*(?:[│ ]   )*(?:[├└]── )?)(\w+)\s", line + " ")
        if match is None or not match[2][0].isupper():
            continue
        depth = len(match[1])
        while parents and parents[-1][0] >= depth:
            parents.pop()
        drawn[match[2]] = parents[-1][1] if parents else None
        parents.append((depth, match[2]))
    classes = _error_classes()
    assert sorted(drawn) == sorted(classes)
    for name, parent in drawn.items():
        base = classes[name].__bases__[0]
        assert base is Exception if parent is None else base.__name__ == parent, name
    assert sorted(errors.__all__) == sorted(classes)


def test_no_module_defines_an_error_of_its_own() -> None:
    names = set(_error_classes())
    elsewhere = []
    for path in sorted(SOURCE.rglob("*.py")):
        if path.name == "errors.py" and path.parent == SOURCE:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and any(
                    isinstance(base, ast.Name) and base.id in names for base in node.bases):
                elsewhere.append(f"{path.relative_to(SOURCE)}: {node.name}")
    assert elsewhere == []
