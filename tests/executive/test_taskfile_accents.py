"""Task files name things with or without accents (issue 22); steps take the world's spelling."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.app import RunSettings, build_run
from homebot.errors import TaskError
from homebot.executive.taskfile import task_from_text
from homebot.sim import PERSON_PREFIX
from homebot.world import World

CASA = Path(__file__).resolve().parents[1] / "world" / "data" / "casa.yaml"
TASK = """\
description: bring the crème brûlée to Patrícia
steps:
  - {skill: navigate, to: MESA DA COZINHA}
  - {skill: find_object, object: creme brulee, placement: mesa da cozinha}
  - {skill: pick, object: creme brulee}
  - {skill: find_person, person: {name: patricia}, room: salao}
  - {skill: give, person: PATRICIA}
"""


def test_names_are_bound_to_the_world_spelling_and_the_task_succeeds() -> None:
    world = World.load(CASA)
    task = task_from_text(TASK, world)
    assert task.description == "bring the crème brûlée to Patrícia"
    assert [step.args for step in task.steps] == [
        {"to": "mesa da cozinha"}, {"object": "crème brûlée", "placement": "mesa da cozinha"},
        {"object": "crème brûlée"}, {"person": {"name": "Patrícia"}, "room": "salão"},
        {"person": "Patrícia"}]
    run = build_run(RunSettings(world=world, seed=0))
    assert run.run(task).success
    assert run.simulation.object_location["crème brûlée"] == PERSON_PREFIX + "Patrícia"


def test_an_unknown_name_is_suggested_with_its_accents() -> None:
    with pytest.raises(TaskError, match=r"unknown object 'creme brule' .*did you mean "
                                        r"'crème brûlée'"):
        task_from_text("- {skill: pick, object: creme brule}\n", World.load(CASA))
