"""Golog programs name things in any script, with accents (issue 22)."""

from __future__ import annotations

import pytest

from homebot.errors import GologError
from homebot.golog.syntax import parse_program


def test_names_with_accents_are_one_name_each() -> None:
    program = parse_program("pick(crème_brûlée); give(Patrícia); say(Søren)")
    assert str(program) == "pick(crème_brûlée); give(Patrícia); say(Søren)"


def test_a_name_still_cannot_start_with_a_digit() -> None:
    with pytest.raises(GologError):
        parse_program("pick(1crème)")
