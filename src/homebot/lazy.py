"""Packages that import their parts on first use (PEP 562), so a one-shot command pays
only for what it touches.

A lazy package's ``__init__`` imports its parts under ``if TYPE_CHECKING:`` (what type
checkers and readers see) and ends with ``__getattr__ = lazy_exports(globals())``.
At run time ``from homebot.geometry import Pose`` then imports ``homebot.geometry.pose``
when first asked, not every other part (numpy, scipy, pydantic ...) with it. The imports
under ``TYPE_CHECKING`` are the one list of what comes from where: it is read from the
``__init__``'s source on the first name asked for.
"""

from __future__ import annotations

import ast
import importlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(namespace: dict[str, Any]) -> Callable[[str], object]:
    """A module ``__getattr__`` for the package whose ``globals()`` are ``namespace``. A
    name is imported once, then kept in the namespace, as an eager import leaves it."""
    package = namespace["__name__"]
    origins: dict[str, str] = {}  #: name -> the module it comes from, read on first use

    def __getattr__(name: str) -> object:
        if not origins:
            origins.update(_type_checking_imports(namespace["__file__"]))
        module = origins.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = namespace[name] = getattr(importlib.import_module(module), name)
        return value

    return __getattr__


def _type_checking_imports(init_file: str) -> dict[str, str]:
    """name -> module, for each ``from MODULE import name`` under ``if TYPE_CHECKING:``."""
    tree = ast.parse(Path(init_file).read_text(encoding="utf-8"))
    origins: dict[str, str] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for statement in node.body:
                if isinstance(statement, ast.ImportFrom) and statement.module:
                    for alias in statement.names:
                        origins[alias.asname or alias.name] = statement.module
    return origins
