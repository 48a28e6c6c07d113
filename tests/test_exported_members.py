"""Each package's ``__all__`` lists exactly what it exposes (no more, no less)."""

from __future__ import annotations

import importlib
import types

import pytest

PACKAGES = ["homebot", "homebot.geometry", "homebot.world", "homebot.navigation",
            "homebot.robot", "homebot.sim", "homebot.skills", "homebot.executive",
            "homebot.scenarios", "homebot.app", "homebot.viz", "homebot.speech", "homebot.web"]


@pytest.mark.parametrize("name", PACKAGES)
def test_all_lists_exactly_the_public_names(name: str) -> None:
    package = importlib.import_module(name)
    public = {attribute for attribute, value in vars(package).items()
              if (not attribute.startswith("_") or attribute == "__version__")
              and not isinstance(value, types.ModuleType)
              and attribute != "annotations"}
    assert set(package.__all__) == public
