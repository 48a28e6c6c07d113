"""Scripted answers are found whatever accents or case the question is asked with (issue 22)."""

from __future__ import annotations

from pathlib import Path

from homebot.sim import ScriptedResponder, normalise_question
from homebot.world import World

CASA = Path(__file__).resolve().parents[1] / "world" / "data" / "casa.yaml"


def test_questions_are_keyed_folded() -> None:
    assert normalise_question("¿Qué comes, José?") == "que comes jose"
    assert normalise_question("What is your NAME?") == "what is your name"


def test_a_scripted_answer_is_found_without_the_accents() -> None:
    jose = World.load(CASA).people["José"].model_copy(
        update={"answers": {"o que você quer beber": "café com leite"}})
    responder = ScriptedResponder()
    assert responder(jose, "O que voce quer beber?") == "café com leite"
    assert responder(jose, "what is your name") == "José"
