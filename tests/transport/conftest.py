"""A DDS domain per test run (and per test), so parallel runs never hear each other."""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterator

import pytest

# Domain ids 20..119 by process, then stepped by the test's number, on loopback only
# (bench transport uses 186..230; 0, ROS 2's default, is left to real robots).
_NEXT = itertools.count()


@pytest.fixture
def domain_id() -> Iterator[int]:
    yield 20 + (os.getpid() * 7 + next(_NEXT)) % 100
