"""From words to the referent: "the left mug" is parsed, searched for, resolved and handed over."""

from __future__ import annotations

from homebot.app import RunSettings, build_run
from homebot.language.parser import parse_command
from homebot.language.vocabulary import Vocabulary
from homebot.world import World


def _world() -> World:
    data = World.load("apartment").to_dict()
    data["categories"].append({"name": "mug", "plural": "mugs"})
    # the kitchen table (centre 9.5, 1.8) faces north: seen from there, east is left
    data["objects"] += [
        {"name": "red mug", "category": "mug", "placement": "kitchen table",
         "position": [9.0, 1.8]},
        {"name": "green mug", "category": "mug", "placement": "kitchen table",
         "position": [9.45, 1.9]},
        {"name": "blue mug", "category": "mug", "placement": "kitchen table",
         "position": [10.0, 1.75]},
    ]
    return World.from_dict(data)


def _given(command: str) -> tuple[str | None, list[str]]:
    world = _world()
    parsed = parse_command(command, Vocabulary.from_world(world))
    assert parsed, parsed
    run = build_run(RunSettings(world=world, seed=4))
    run.run(parsed.to_task())
    truth = run.simulation.object_location
    handed = [name for name in ("red mug", "green mug", "blue mug")
              if truth[name] == f"person:{world.model.operator}"]
    spoken = [event.data["text"] for event in run.context.events.of_kind("speech")]
    return (handed[0] if handed else None), spoken


def test_the_left_mug_is_the_one_on_the_viewers_left() -> None:
    assert _given("bring me the left mug from the kitchen table")[0] == "blue mug"
    assert _given("bring me the mug on the right from the kitchen table")[0] == "red mug"


def test_the_robot_asks_when_the_words_fit_no_mug_well() -> None:
    handed, spoken = _given("bring me the front mug from the kitchen table")
    assert handed is None  # the mugs stand side by side: none is "the front one"
    assert any("Which mug do you mean" in text or "Do you mean" in text for text in spoken)
