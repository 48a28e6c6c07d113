"""``homebot bench perception``: object figures judged by the scenes' truth; bad input."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("sklearn")

from homebot.app.perception import trained_recogniser
from homebot.cli import main
from homebot.trials.tabletop import object_figures
from homebot.world import World

WORLD = """\
name: two things
rooms:
  - {name: hall, polygon: [[0, 0], [4, 0], [4, 4], [0, 4]]}
placements:
  - {name: table, category: table, room: hall, center: [3, 2], size: [1, 1]}
objects:
  - {name: cola, category: drink, placement: table}
  - {name: apple, category: fruit, placement: table}
  - {name: cereal, category: food, placement: table}
robot:
  pose: [1, 1, 0]
"""


def test_object_figures_are_judged_against_the_truth() -> None:
    figures = object_figures(World.from_yaml_text(WORLD), 4, 11, train=trained_recogniser)
    assert figures["scenes"] == 4 and figures["objects"] >= 4
    assert 0.0 <= figures["precision"] <= 1.0 and figures["recall"] >= 0.75
    assert figures["category_accuracy"] >= 0.75
    assert figures["median_position_error_cm"] < 3.0
    assert set(figures["targets_met"]) == {"precision", "recall", "category_accuracy",
                                           "median_position_error_cm", "cpu_ms_per_frame"}


def test_a_world_without_objects_says_so() -> None:
    empty = WORLD.split("objects:")[0] + "robot:\n  pose: [1, 1, 0]\n"
    assert "no objects" in object_figures(World.from_yaml_text(empty), 2, 1,
                                     train=trained_recogniser)["status"]


def test_bad_arguments_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "perception", "--scenes", "0"]) == 2
    assert main(["bench", "perception", "--world", str(tmp_path / "none.yaml")]) == 2
    err = capsys.readouterr().err
    assert "--scenes" in err and "no such file" in err and "Traceback" not in err
