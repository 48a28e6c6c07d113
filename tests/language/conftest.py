"""Shared fixtures of the language tests: worlds, vocabularies, the shared data paths."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.language import Vocabulary
from homebot.world import World

SHARED = Path(__file__).resolve().parents[3] / "shared" / "data"
ROBOCUP_DIRECTORY = SHARED / "robocup" / "CompetitionTemplate"
GPSR_COMMANDS = SHARED / "gpsr" / "competition_template_commands.tsv"


@pytest.fixture(scope="session")
def apartment() -> World:
    return World.load("apartment")


@pytest.fixture(scope="session")
def vocabulary(apartment: World) -> Vocabulary:
    return Vocabulary.from_world(apartment)


@pytest.fixture(scope="session")
def shared_robocup() -> Path:
    if not ROBOCUP_DIRECTORY.is_dir() or not GPSR_COMMANDS.is_file():
        pytest.skip("the shared acceptance data (../shared/data) is absent")
    return ROBOCUP_DIRECTORY


@pytest.fixture(scope="session")
def shared_gpsr_commands(shared_robocup: Path) -> Path:
    """The shared 1000 GPSR commands (a TSV); skipped as ``shared_robocup`` is."""
    return GPSR_COMMANDS
