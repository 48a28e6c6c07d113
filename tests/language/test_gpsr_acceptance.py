"""The shared 1000 GPSR commands parse to their expected skill sequences (>= 99 %)."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from gpsr_expectations import Expectations, Names

from homebot.language import Vocabulary, parse_command
from homebot.language.generator import generate_commands
from homebot.world import World
from homebot.world.robocup import world_from_robocup

pytestmark = pytest.mark.acceptance


def test_shared_commands_parse_to_expected_steps(shared_robocup: Path,
                                                 shared_gpsr_commands: Path) -> None:
    expectations = Expectations(Names.from_directory(str(shared_robocup)))
    vocabulary = Vocabulary.from_world(World.from_dict(world_from_robocup(shared_robocup)))
    with shared_gpsr_commands.open(encoding="utf-8") as handle:
        rows = list(csv.reader(handle, delimiter="\t"))
    assert len(rows) == 1000
    wrong = []
    for _group, kind, followups, _dataset, text in rows:
        expected = expectations.expected(kind, followups, text)
        result = parse_command(text, vocabulary)
        if not result or result.to_dict()["steps"] != expected:
            wrong.append(text)
    assert len(wrong) <= 10, wrong[:10]


def test_generated_commands_over_the_robocup_world(shared_robocup: Path) -> None:
    world = World.from_dict(world_from_robocup(shared_robocup))
    vocabulary = Vocabulary.from_world(world)
    commands = generate_commands(world, 500, seed=7)
    right = sum(parse_command(text, vocabulary).to_dict()["steps"]
                == [step.to_dict() for step in steps] for text, steps in commands)
    assert right >= 0.99 * len(commands)
