"""Each package's ``__all__`` lists exactly what it exposes (no more, no less)."""

from __future__ import annotations

import importlib
import types

import pytest

PACKAGES = ["homebot", "homebot.geometry", "homebot.world", "homebot.space",
            "homebot.knowledge", "homebot.navigation",
            "homebot.robot", "homebot.sim", "homebot.skills", "homebot.executive",
            "homebot.scenarios", "homebot.app", "homebot.viz", "homebot.speech", "homebot.web"]


@pytest.mark.parametrize("name", PACKAGES)
def test_all_lists_exactly_the_public_names(name: str) -> None:
    package = importlib.import_module(name)
    for exported in package.__all__:  # a lazy package (homebot.lazy) imports each when asked
        getattr(package, exported)
    public = {attribute for attribute, value in vars(package).items()
              if (not attribute.startswith("_") or attribute == "__version__")
              and not isinstance(value, types.ModuleType)
              and attribute not in {"annotations", "TYPE_CHECKING", "lazy_exports"}}
    assert set(package.__all__) == public
