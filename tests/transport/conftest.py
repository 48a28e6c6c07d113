"""A DDS domain per test run (and per test), so parallel runs never hear each other."""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterator

import pytest

# Domain ids 120..219 by process, then stepped by the test's number: loopback only.
_NEXT = itertools.count()


@pytest.fixture
def domain_id() -> Iterator[int]:
    yield 120 + (os.getpid() * 7 + next(_NEXT)) % 100
