"""Fixtures for the knowledge-base tests: the shipped KBs."""

from __future__ import annotations

import pytest

from homebot.knowledge import KnowledgeBase


@pytest.fixture
def animals() -> KnowledgeBase:
    """Listing 2: birds, eagles, penguins, Pete and Arthur."""
    return KnowledgeBase.load("animals")


@pytest.fixture
def butler() -> KnowledgeBase:
    """Listing 3: the butler's KB with the user's preferences."""
    return KnowledgeBase.load("butler")
