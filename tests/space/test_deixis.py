"""Pointing at a place on a table, "put the red cup there", and Order Cups from both."""

from __future__ import annotations

import argparse

from homebot.cli.scenario import run_builder
from homebot.geometry import Ray
from homebot.space.deixis import deictic_request, pointed_place

PLACES = {"p1": (0.0, 0.45), "p2": (0.0, 0.15), "p3": (0.0, -0.15), "p4": (0.0, -0.45)}


def test_the_place_pointed_at_or_a_question_when_between_two() -> None:
    place, _ = pointed_place(Ray((1.0, 0.15, 1.4), (0.7, 0.15, 1.2)), PLACES, 0.75, 1.67)
    assert place == "p2"
    between = Ray((1.0, 0.0, 1.4), (0.7, 0.0, 1.2))  # between p2 and p3
    assert pointed_place(between, PLACES, 0.75, 1.67)[0] is None


def test_the_request_names_what_goes_there() -> None:
    assert deictic_request("put the red cup there") == "red cup"
    assert deictic_request("Please place the blue cup over there.") == "blue cup"
    assert deictic_request("bring me a cup") is None


def test_order_cups_from_speech_and_pointing_takes_the_fewest_moves() -> None:
    from homebot.scenarios.library import order_cups_pointing

    for seed in (1, 3):
        summary = order_cups_pointing.run(argparse.Namespace(
            seed=seed, goal="green,blue,red", spread=0.04, horizon=4), None, run_builder())
        assert summary["understood"] == ["green", "blue", "red"]
        assert summary["success"] and summary["moves"] == summary["fewest_moves"]
