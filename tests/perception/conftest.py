"""Shared fixtures of the perception tests."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest


@pytest.fixture(scope="session")
def detector() -> Any:
    """A small face cascade trained once on rendered strangers' faces and backgrounds."""
    pytest.importorskip("sklearn")
    from homebot.perception.faces import FaceDetector
    from homebot.sim.faces import background_patch, face_identity, face_view

    rng = np.random.default_rng(5)
    strangers = [face_identity(f"stranger{i}", 9) for i in range(12)]
    views = [face_view(strangers[i % 12], rng) for i in range(80)]
    found = FaceDetector(features=200, stumps=(8, 40))
    found.train([image for image, _ in views], [window for _, window in views],
                [background_patch(rng) for _ in range(60)])
    return found
