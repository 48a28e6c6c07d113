"""Whatever a task file holds, loading it succeeds or raises ``HomebotError``, never a crash."""

from __future__ import annotations

from typing import Any

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.app import RunSettings, build_run, disturbed
from homebot.errors import HomebotError
from homebot.executive.taskfile import task_from_text
from homebot.navigation import Navigator
from homebot.skills import SKILLS
from homebot.world import World

_WORLD = World.load("apartment")
_NAVIGATOR = Navigator(_WORLD)
_NAMES = st.sampled_from(["kitchen", "fridge", "cola", "drink", "operator", "left", "$result",
                          "waving", "kitchen door", "", "nowhere", "Küche", "[/b]"])
_SCALARS = (st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8)
            | _NAMES)
_VALUES = st.recursive(_SCALARS, lambda inner: st.lists(inner, max_size=3)
                       | st.dictionaries(st.text(max_size=6) | st.integers() | _NAMES, inner,
                                         max_size=3), max_leaves=8)
_ARGUMENTS = st.sampled_from(["to", "object", "placement", "room", "person", "door", "text",
                              "question", "hand", "exclude", "info", "property", "1"])
_STEPS = st.fixed_dictionaries(
    {"skill": st.sampled_from(sorted(SKILLS)) | _SCALARS},
    optional={"to": _VALUES, "object": _VALUES, "person": _VALUES},
).flatmap(lambda step: st.dictionaries(_ARGUMENTS, _VALUES, max_size=3).map(
    lambda extra: {**extra, **step}))
_NOISE = st.text(alphabet=st.sampled_from(list("[]{}:,-'\"#&*!|>?% \n\tabc019.é")), max_size=12)


def _loads(text: str) -> None:
    try:
        task_from_text(text, _WORLD, "fuzz.yaml")
    except HomebotError as error:
        assert str(error)


@settings(max_examples=300, deadline=None)
@given(st.lists(_STEPS | _VALUES, max_size=4), st.booleans(), _VALUES)
def test_random_steps_are_loaded_or_rejected_with_a_homebot_error(
        steps: list[Any], wrapped: bool, description: Any) -> None:
    document: Any = {"description": description, "steps": steps} if wrapped else steps
    _loads(yaml.safe_dump(document, allow_unicode=True))


@settings(max_examples=200, deadline=None)
@given(_VALUES)
def test_any_yaml_document_is_loaded_or_rejected(value: Any) -> None:
    _loads(yaml.safe_dump(value, allow_unicode=True))


_GOOD = ("description: bring the cola\nsteps:\n  - {skill: navigate, to: fridge}\n"
         "  - {skill: find_object, object: cola, placement: fridge}\n"
         "  - {skill: pick, object: cola}\n  - {skill: give, person: operator}\n")


@settings(max_examples=200, deadline=None)
@given(st.integers(0, len(_GOOD)), st.integers(0, 20), _NOISE)
def test_a_damaged_task_file_is_rejected_with_a_homebot_error(start: int, cut: int,
                                                              noise: str) -> None:
    _loads(_GOOD[:start] + noise + _GOOD[start + cut:])


def test_the_undamaged_task_loads() -> None:
    assert len(task_from_text(_GOOD, _WORLD).steps) == 4
    with pytest.raises(HomebotError):
        task_from_text("- {skill: navigate, to: [kitchen]}", _WORLD)


_PEOPLE = [*_WORLD.people, "operator"]
_GOOD_VALUES = {
    "to": [*_WORLD.placements, *_WORLD.rooms, *_PEOPLE], "placement": list(_WORLD.placements),
    "room": list(_WORLD.rooms), "object": [*_WORLD.objects, *_WORLD.categories],
    "door": list(_WORLD.doors), "text": ["hi", "$result"], "info": ["your name"],
    "person": [*_PEOPLE, {"name": "Maria"}, {"gesture": "waving"}, {}],
    "question": ["what is your name"], "hand": ["left", "foot"], "property": ["biggest"],
    "exclude": [["fridge"], []],
    "spatial": [["left"], "close to the plate", [{"kind": "side", "value": "right"}], "up",
                [3]]}


@st.composite
def _valid_steps(draw: st.DrawFn) -> dict[str, Any]:
    skill = SKILLS[draw(st.sampled_from(sorted(SKILLS)))]
    names = [*skill.required, *draw(st.lists(st.sampled_from(skill.optional or ("",)),
                                             max_size=2, unique=True))]
    return {"skill": skill.name, **{name: draw(st.sampled_from(_GOOD_VALUES[name]))
                                    for name in names if name}}


@settings(max_examples=60, deadline=None)
@given(st.lists(_valid_steps(), min_size=1, max_size=5), st.integers(0, 3), st.booleans(),
       st.integers(0, 1000))
def test_a_valid_task_runs_to_a_report_whatever_happens(steps: list[dict[str, Any]], level: int,
                                                        monitoring: bool, seed: int) -> None:
    try:
        task = task_from_text(yaml.safe_dump(steps), _WORLD)
    except HomebotError:
        return
    run = build_run(RunSettings(
        world=_WORLD, seed=seed, navigator=_NAVIGATOR, monitoring=monitoring,
        disturbances=disturbed(level) if level else None))
    report = run.run(task)
    assert report.success or report.reason
