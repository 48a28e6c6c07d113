"""Referring expressions: modifiers read from words, resolved by degrees, questions when close."""

from __future__ import annotations

from homebot.space.referring import Modifier, Scene, resolve, split_spatial

VIEWER = (0.0, -1.0)  # the viewer stands south of the table and looks north


def _scene(points: dict[str, tuple[float, float]]) -> Scene:
    categories = {name: name.split()[-1] for name in points}
    return Scene(points, categories, 1.44, VIEWER)


def test_modifiers_are_taken_out_of_the_command() -> None:
    assert split_spatial("get me the left cup on the table") == (
        "get me the cup on the table", [Modifier("side", "left", None, "the left")])
    rest, modifiers = split_spatial("bring me the cup close to the plate")
    assert rest == "bring me the cup"
    assert modifiers == [Modifier("relation", "near", "plate", "close to the plate")]
    assert split_spatial("take the bottle behind the bowl to the kitchen")[1][0].value == "back"
    assert split_spatial("find the chair near the window")[1][0].relatum == "window"


def test_words_that_are_not_spatial_modifiers_stay() -> None:
    for text in ("give it to the person pointing to the left in the kitchen",
                 "find the person raising the left arm", "bring me the apple"):
        assert split_spatial(text) == (text, [])


def test_the_left_cup_is_the_one_left_of_every_other() -> None:
    scene = _scene({"red cup": (-0.4, 0.0), "green cup": (0.0, 0.05), "blue cup": (0.4, 0.0)})
    cups = ["red cup", "green cup", "blue cup"]
    assert resolve(cups, split_spatial("the left cup")[1], scene).referent == "red cup"
    assert resolve(cups, split_spatial("the cup on the right")[1], scene).referent == "blue cup"


def test_two_cups_one_behind_the_other_make_the_robot_ask() -> None:
    scene = _scene({"red cup": (-0.30, 0.0), "green cup": (-0.31, 0.3), "blue cup": (0.4, 0.0)})
    answer = resolve(["red cup", "green cup", "blue cup"], split_spatial("the left cup")[1],
                     scene, noun="cup")
    assert answer.referent is None
    assert answer.question is not None and "Which cup" in answer.question


def test_close_to_picks_the_nearest_and_asks_when_two_are_as_near() -> None:
    plate = (0.0, 0.0)
    clear = _scene({"the plate": plate, "red cup": (0.1, 0.0), "blue cup": (0.5, 0.2)})
    modifiers = split_spatial("the cup close to the plate")[1]
    assert resolve(["red cup", "blue cup"], modifiers, clear).referent == "red cup"
    tie = _scene({"the plate": plate, "red cup": (0.2, 0.0), "blue cup": (-0.2, 0.01)})
    assert resolve(["red cup", "blue cup"], modifiers, tie).referent is None


def test_behind_is_further_from_the_viewer_and_combined_modifiers_multiply() -> None:
    scene = _scene({"bowl": (0.0, 0.0), "tall bottle": (0.0, 0.2), "small bottle": (0.0, -0.2)})
    bottles = ["tall bottle", "small bottle"]
    assert resolve(bottles, split_spatial("the bottle behind the bowl")[1],
                   scene).referent == "tall bottle"
    assert resolve(bottles, split_spatial("the bottle in front of the bowl")[1],
                   scene).referent == "small bottle"


def test_a_missing_relatum_is_a_question() -> None:
    scene = _scene({"red cup": (0.0, 0.0), "blue cup": (0.3, 0.0)})
    answer = resolve(["red cup", "blue cup"], split_spatial("the cup near the plate")[1], scene,
                     noun="cup")
    assert answer.referent is None and "plate" in (answer.question or "")


def test_the_benchmark_never_picks_a_wrong_object_confidently() -> None:
    import argparse

    from homebot.bench.referring import run

    figures = run(argparse.Namespace(scenes=60, seed=5, noise=0.01, margin=0.15, repeats=1))
    assert figures["scenes"] == 60 and figures["clear"] > 20
    assert figures["confident_wrong"] == 0
    assert figures["acceptable"] >= 0.9


def test_modifiers_from_a_task_step_are_checked() -> None:
    import pytest

    from homebot.space.referring import modifiers_from

    assert [m.value for m in modifiers_from(["left", "close to the plate"])] == ["left", "near"]
    assert modifiers_from("behind the bowl")[0].relatum == "bowl"
    for bad in ("up", [3], [], 5):
        with pytest.raises(ValueError, match="spatial modifier"):
            modifiers_from(bad)
