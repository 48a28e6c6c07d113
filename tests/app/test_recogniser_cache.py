"""The trained object recogniser is kept on disk, and a new process reads it back unchanged."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import homebot.app.perception as app_perception
from homebot.app.cache import CACHE_DIRECTORY_VARIABLE
from homebot.app.perception import labelled_frames, trained_recogniser
from homebot.perception.recognition import training_examples
from homebot.world import World, object_catalogue


def test_a_recogniser_trained_once_is_read_back_from_disk_with_the_same_answers(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(CACHE_DIRECTORY_VARIABLE, str(tmp_path))
    catalogue = dict(list(object_catalogue(World.load("apartment")).items())[:3])
    app_perception._trained.cache_clear()
    trained = trained_recogniser(catalogue)
    assert len(list(tmp_path.glob("recogniser-*.pickle"))) == 1

    def never_train(*_: object) -> None:
        raise AssertionError("trained again although the disk held the recogniser")

    app_perception._trained.cache_clear()  # as a new process would start
    monkeypatch.setattr(app_perception, "_train", never_train)
    loaded = trained_recogniser(catalogue)
    assert loaded is not trained
    frames = labelled_frames(catalogue, 3, np.random.default_rng(5))
    features, _ = training_examples(frames, np.random.default_rng(6))
    assert loaded.predict(np.asarray(features)) == trained.predict(np.asarray(features))
    app_perception._trained.cache_clear()
