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
