"""GPSR end to end: generated commands are parsed and carried out in the simulated home."""

from __future__ import annotations

from homebot.bench.gpsr import execute_commands
from homebot.task import Step
from homebot.trials.gpsr import feasible
from homebot.world import World


def test_two_hundred_generated_commands_are_carried_out(apartment: World) -> None:
    result = execute_commands(apartment, 200, seed=1)
    assert result.commands == 200
    assert result.succeeded / result.commands >= 0.95
    assert result.parsed_as_expected / result.commands >= 0.99


def test_commands_about_people_who_are_not_there_are_not_feasible(apartment: World) -> None:
    waving_in_kitchen = [Step("find_person", {"person": {"gesture": "waving"},
                                              "room": "kitchen"})]
    waving_in_office = [Step("find_person", {"person": {"gesture": "waving"}, "room": "office"})]
    assert not feasible(apartment, waving_in_kitchen)
    assert feasible(apartment, waving_in_office)
    assert not feasible(apartment, [Step("find_object", {"object": "fruit", "room": "bedroom"})])
    assert feasible(apartment, [Step("find_object", {"object": "fruit", "room": "kitchen"})])
