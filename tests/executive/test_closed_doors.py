"""Doors that start closed in the world file: planned through, opened on arrival (issue 14)."""

from __future__ import annotations

from typing import Any

from homebot.app import RunSettings, build_run
from homebot.sim import PERSON_PREFIX
from homebot.task import Step, Task
from homebot.world import World


def _apartment_with(door: str, state: str, apartment: World) -> World:
    data: dict[str, Any] = apartment.to_dict()
    for entry in data["doors"]:
        if entry["name"] == door:
            entry["state"] = state
    return World.from_dict(data)


def _bring_picture_frame() -> Task:
    return Task((Step("navigate", {"to": "bedside table"}),
                 Step("find_object", {"object": "picture frame", "placement": "bedside table"}),
                 Step("pick", {"object": "picture frame"}),
                 Step("navigate", {"to": "operator"}), Step("give", {"person": "operator"})))


def test_a_door_closed_in_the_world_file_on_the_only_route_is_opened(apartment: World) -> None:
    # The bedroom has one door; the world file says it is closed, so the robot believes it shut.
    world = _apartment_with("bedroom door", "closed", apartment)
    run = build_run(RunSettings(world=world))
    assert "bedroom door" in run.context.beliefs.closed_doors
    report = run.run(_bring_picture_frame())
    assert report.success, report.reason
    assert run.simulation.object_location["picture frame"] == PERSON_PREFIX + "Alex"
    events = run.simulation.events.events
    kinds = [(event.kind, event.data.get("skill"), event.data.get("error")) for event in events]
    # The door protocol ran on arrival: blocked at the door, recovery, open_door verified.
    assert ("recovery", "navigate", "door_closed") in kinds
    opened = [event for event in events if event.kind == "skill.status"
              and event.data["skill"] == "open_door" and event.data["status"] == "verified"]
    assert len(opened) == 1
    assert report.steps[0].recoveries == ("door_closed",)


def test_a_route_without_closed_doors_is_preferred(apartment: World) -> None:
    # The kitchen has a door to the corridor and an arch to the entrance: with the
    # door believed closed, the robot goes through the arch and opens nothing.
    world = _apartment_with("kitchen door", "closed", apartment)
    run = build_run(RunSettings(world=world))
    report = run.run(Task((Step("navigate", {"to": "fridge"}),)))
    assert report.success
    assert not any(event.kind == "skill.start" and event.data["skill"] == "open_door"
                   for event in run.simulation.events.events)


def test_a_locked_door_on_the_only_route_ends_in_a_failure_naming_it(apartment: World) -> None:
    # Nobody will open it: the robot asks the people it can reach, and they refuse.
    data: dict[str, Any] = _apartment_with("bedroom door", "locked", apartment).to_dict()
    for person in data["people"]:
        person["cooperative"] = False
    run = build_run(RunSettings(world=World.from_dict(data)))
    report = run.run(Task((Step("navigate", {"to": "bed"}),)))
    assert not report.success
    assert "bedroom door" in report.reason
    assert any("could you please open the bedroom door" in text for text in report.speech)
