"""``homebot.app.cache``: a folder the person chooses, and keys that change with the libraries."""

from __future__ import annotations

from pathlib import Path

import pytest

import homebot.app.cache as cache
import homebot.perception.faces as faces_module
from homebot.app.cache import CACHE_DIRECTORY_VARIABLE, cache_directory, cache_key


def test_the_folder_is_the_one_the_variable_names(tmp_path: Path,
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(CACHE_DIRECTORY_VARIABLE, str(tmp_path))
    assert cache_directory() == tmp_path


def test_without_the_variable_the_folder_is_the_users_cache(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(CACHE_DIRECTORY_VARIABLE, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    assert cache_directory() == tmp_path / ".cache" / "homebot"


def test_the_tests_never_use_the_users_cache() -> None:
    assert cache_directory() != Path.home() / ".cache" / "homebot"


def test_the_key_changes_with_what_is_cached_and_with_each_library(
        monkeypatch: pytest.MonkeyPatch) -> None:
    key = cache_key(("Alex",), [faces_module])
    assert key == cache_key(("Alex",), [faces_module])
    assert key != cache_key(("Lisa",), [faces_module])
    assert key != cache_key(("Alex",), [])
    for library in ("scikit-learn", "numpy", "opencv-python-headless"):
        with monkeypatch.context() as patch:
            patch.setattr(cache, "_version", lambda name, changed=library: (
                "0.0-other" if name == changed else "1.0"))
            upgraded = cache_key(("Alex",), [faces_module])
            patch.setattr(cache, "_version", lambda name: "1.0")
            assert upgraded != cache_key(("Alex",), [faces_module]), library


def test_the_key_changes_with_homebots_version(monkeypatch: pytest.MonkeyPatch) -> None:
    key = cache_key(("Alex",), [faces_module])
    monkeypatch.setattr("homebot.__version__", "99.0")
    assert cache_key(("Alex",), [faces_module]) != key
