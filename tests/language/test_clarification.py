"""Incomplete commands get a question back; impossible ones a refusal naming the reason."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from homebot.errors import LanguageError
from homebot.language import ParseStatus, Vocabulary, parse_command

CASES: list[dict[str, Any]] = yaml.safe_load(
    (Path(__file__).parent / "clarifications.yaml").read_text(encoding="utf-8"))


def test_there_are_at_least_40_clarification_and_refusal_cases() -> None:
    assert sum(case["status"] in {"clarify", "reject"} for case in CASES) >= 40


@pytest.mark.parametrize("case", CASES, ids=[case["say"] for case in CASES])
def test_clarify_or_reject(case: dict[str, Any], vocabulary: Vocabulary) -> None:
    result = parse_command(case["say"], vocabulary)
    assert result.status == ParseStatus(case["status"])
    message = (result.question or result.reason or "").lower()
    for word in case["mention"]:
        assert word.lower() in message
    if result.status is not ParseStatus.OK:
        assert result.steps == []
        assert not result


def test_clarify_result_serialises_with_its_question(vocabulary: Vocabulary) -> None:
    data = parse_command("Bring me the drink", vocabulary).to_dict()
    assert data["status"] == "clarify" and data["steps"] == [] and "question" in data


def test_reject_result_serialises_with_its_reason(vocabulary: Vocabulary) -> None:
    data = parse_command("Fetch the kitchen", vocabulary).to_dict()
    assert data["status"] == "reject" and "reason" in data and "question" not in data


@pytest.mark.parametrize("text", ["", "   ", "x" * 2000])
def test_empty_or_absurd_input_is_a_language_error(text: str, vocabulary: Vocabulary) -> None:
    with pytest.raises(LanguageError):
        parse_command(text, vocabulary)


def test_a_category_said_with_a_place_stays_category_level(vocabulary: Vocabulary) -> None:
    result = parse_command("Bring me something to drink", vocabulary)
    assert result.to_dict()["steps"][0] == {"skill": "find_object", "object": "drink"}
