"""Our generator: deterministic by seed, every command type, and the parser agrees (>= 99 %)."""

from __future__ import annotations

import pytest

from homebot.errors import LanguageError
from homebot.language import Vocabulary, parse_command
from homebot.language.generator import COMMAND_TYPES, generate_commands
from homebot.world import World


def test_same_seed_same_commands(apartment: World) -> None:
    assert generate_commands(apartment, 20, seed=3) == generate_commands(apartment, 20, seed=3)
    assert generate_commands(apartment, 20, seed=3) != generate_commands(apartment, 20, seed=4)


def test_commands_use_only_world_names(apartment: World) -> None:
    for text, steps in generate_commands(apartment, 50, seed=1):
        assert text[0].isupper() and steps
        for step in steps:
            target = step.args.get("to")
            assert target is None or target == "operator" or target in apartment.rooms or (
                target in apartment.placements)


@pytest.mark.parametrize("world_name", ["apartment", "supermarket"])
def test_parser_agrees_with_generated_expectations(world_name: str) -> None:
    world = World.load(world_name)
    vocabulary = Vocabulary.from_world(world)
    commands = generate_commands(world, 300, seed=11)
    wrong = [text for text, steps in commands
             if parse_command(text, vocabulary).to_dict()["steps"]
             != [step.to_dict() for step in steps]]
    assert len(wrong) <= 0.01 * len(commands), wrong[:5]


def test_there_are_many_command_types() -> None:
    assert len(COMMAND_TYPES) >= 10


def test_a_world_without_people_cannot_generate(apartment: World) -> None:
    data = apartment.to_dict()
    data["people"] = []
    data.pop("operator", None)
    with pytest.raises(LanguageError, match="no people"):
        generate_commands(World.from_dict(data), 5, seed=0)
