"""``__all__`` lists what ``homebot.knowledge``'s modules define (the package's own
``__all__``: ``tests/test_exported_members.py``)."""

from __future__ import annotations

import importlib
import pkgutil

import pytest

import homebot.knowledge

MODULES = sorted(m.name for m in pkgutil.iter_modules(homebot.knowledge.__path__))


@pytest.mark.parametrize("name", MODULES)
def test_every_module_lists_only_what_it_defines(name: str) -> None:
    module = importlib.import_module(f"homebot.knowledge.{name}")
    assert module.__doc__ and len(module.__doc__.strip().splitlines()[0]) > 10
    for exported in module.__all__:
        assert hasattr(module, exported), f"{name}.__all__ names missing {exported}"


@pytest.mark.parametrize("name", MODULES)
def test_modules_stay_small(name: str) -> None:
    module = importlib.import_module(f"homebot.knowledge.{name}")
    assert module.__file__ is not None
    with open(module.__file__, encoding="utf-8") as source:
        assert sum(1 for _ in source) <= 500
