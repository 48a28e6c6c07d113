"""Shared fixtures: the shipped worlds and one navigator per world (rasterising costs time)."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.navigation import Navigator
from homebot.world import World

SHARED = Path(__file__).resolve().parents[1].parent / "shared"


@pytest.fixture(scope="session")
def apartment() -> World:
    return World.load("apartment")


@pytest.fixture(scope="session")
def apartment_navigator(apartment: World) -> Navigator:
    return Navigator(apartment)


@pytest.fixture(scope="session")
def supermarket() -> World:
    return World.load("supermarket")


@pytest.fixture(autouse=True)
def _private_cache(tmp_path_factory: pytest.TempPathFactory,
                   monkeypatch: pytest.MonkeyPatch) -> None:
    """Runs remember their event log in the project (and caches); tests keep theirs private."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.mktemp("cache")))
    monkeypatch.setenv("HOMEBOT_PROJECT", str(tmp_path_factory.mktemp("project")))
