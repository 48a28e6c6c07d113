"""Shared fixtures: the shipped worlds and one navigator per world (rasterising costs time)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from hypothesis import settings

from homebot.app.cache import CACHE_DIRECTORY_VARIABLE
from homebot.navigation import Navigator
from homebot.world import World

SHARED = Path(__file__).resolve().parents[1].parent / "shared"


# Tests assert behaviour, not time (timing is the benchmarks'): on a loaded machine one
# example can take seconds, which hypothesis's default 200 ms deadline reads as a failure.
settings.register_profile("homebot", deadline=None)
settings.load_profile("homebot")

#: ``fails_cleanly(status, expected)``: a command exited 2 with one line on stderr holding
#: ``expected`` and no traceback anywhere; gives that line
FailsCleanly = Callable[[int, str], str]


@pytest.fixture
def fails_cleanly(capsys: pytest.CaptureFixture[str]) -> FailsCleanly:
    def check(status: int, expected: str) -> str:
        captured = capsys.readouterr()
        assert status == 2
        assert expected in captured.err
        assert "Traceback" not in captured.err + captured.out
        assert len(captured.err.strip().splitlines()) == 1  # one line, however long
        return captured.err

    return check


@pytest.fixture(scope="session")
def apartment() -> World:
    return World.load("apartment")


@pytest.fixture(scope="session")
def apartment_navigator(apartment: World) -> Navigator:
    return Navigator(apartment)


@pytest.fixture(scope="session")
def supermarket() -> World:
    return World.load("supermarket")


@pytest.fixture(scope="session", autouse=True)
def _test_model_cache(request: pytest.FixtureRequest,
                      tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """Trained models go to a folder of the tests' own, never the user's ~/.cache/homebot.

    It is pytest's cache folder (``.pytest_cache/d/homebot``, emptied by
    ``--cache-clear``), which outlives the session: teaching the robot its household's
    faces takes tens of seconds, once. Without pytest's cache, a folder of this session.
    """
    cache = getattr(request.config, "cache", None)
    folder = cache.mkdir("homebot") if cache is not None else tmp_path_factory.mktemp("models")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv(CACHE_DIRECTORY_VARIABLE, str(folder))
        yield


@pytest.fixture(autouse=True)
def _private_cache(tmp_path_factory: pytest.TempPathFactory,
                   monkeypatch: pytest.MonkeyPatch) -> None:
    """Runs remember their event log in the project (and caches); tests keep theirs private."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.mktemp("cache")))
    monkeypatch.setenv("HOMEBOT_PROJECT", str(tmp_path_factory.mktemp("project")))
