"""Fixtures for the SitLog tests: the seed paper's text, when ../shared is there."""

from __future__ import annotations

from pathlib import Path

import pytest

SEED = Path(__file__).resolve().parents[2].parent / "shared" / "seeds" / (
    "golem-deliberative-conceptual-inference.txt")


@pytest.fixture(scope="session")
def golem_paper() -> str:
    if not SEED.is_file():
        pytest.skip("the seed papers in ../shared are not here")
    return SEED.read_text(encoding="utf-8")
