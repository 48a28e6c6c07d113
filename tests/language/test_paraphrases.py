"""Hand-written paraphrases of GPSR commands parse to the steps they mean (>= 90 %)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml
from step_notation import parse_steps

from homebot.language import Vocabulary, parse_command

CASES: list[dict[str, Any]] = yaml.safe_load(
    (Path(__file__).parent / "paraphrases.yaml").read_text(encoding="utf-8"))


def _mismatches(vocabulary: Vocabulary) -> list[tuple[str, Any, Any]]:
    wrong = []
    for case in CASES:
        result = parse_command(case["say"], vocabulary)
        got = result.to_dict()["steps"] if result else result.to_dict()
        expected = parse_steps(case["steps"])
        if got != expected:
            wrong.append((case["say"], expected, got))
    return wrong


def test_there_are_at_least_150_varied_paraphrases() -> None:
    texts = [case["say"] for case in CASES]
    assert len(texts) >= 150
    assert len(set(texts)) == len(texts)


def test_at_least_90_percent_of_paraphrases_parse_to_their_steps(
        vocabulary: Vocabulary) -> None:
    wrong = _mismatches(vocabulary)
    rate = 1 - len(wrong) / len(CASES)
    detail = "\n".join(f"{text}\n  expected {e}\n  got      {g}" for text, e, g in wrong)
    assert rate >= 0.90, f"{rate:.1%} right; wrong:\n{detail}"


@pytest.mark.parametrize("notation, expected", [
    ("pick(object=cup)", [{"skill": "pick", "object": "cup"}]),
    ("@give_me", [{"skill": "navigate", "to": "operator"},
                  {"skill": "give", "person": "operator"}]),
    ("find_person(person.name=Maria, room=kitchen)",
     [{"skill": "find_person", "person": {"name": "Maria"}, "room": "kitchen"}]),
])
def test_step_notation(notation: str, expected: list[dict[str, Any]]) -> None:
    assert parse_steps(notation) == expected
