"""A 0.5 m robot passes an 0.8 m doorway without shuttling: it drives through once, also
when the door stands half open with a shelf beside it, without touching the leaf (the
simulator's trail and bumper say so)."""

from __future__ import annotations

import math

import pytest

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.geometry import Pose
from homebot.world import World

pytest.importorskip("cv2")

_FLAT = """
name: two_rooms_narrow_door
rooms:
  - {{name: hall, polygon: [[0, 0], [3, 0], [3, 3], [0, 3]]}}
  - {{name: study, polygon: [[3, 0], [6, 0], [6, 3], [3, 3]]}}
doors:
  - {{name: study door, rooms: [hall, study], position: [3, 1.0], width: 0.8{leaf}}}
categories:
  - {{name: book, plural: books}}
placements:
  - {{name: shelf, category: storage, room: hall, center: [2.75, 1.95], size: [0.4, 0.6]}}
  - {{name: desk, category: table, room: study, center: [5.4, 2.6], size: [1.0, 0.6],
     holds: [book]}}
objects:
  - {{name: atlas, category: book, placement: desk}}
people:
  - {{name: Ada, room: hall, position: [0.6, 2.4]}}
operator: Ada
robot:
  pose: [1.0, 1.6, 0.0]
  radius: 0.25
"""


def _sides(trail: list[tuple[float, float]]) -> list[int]:
    """Which side of the door's wall (x = 3) the robot was on, each time it changed."""
    sides: list[int] = []
    for x, _ in trail:
        side = 1 if x > 3.0 else -1
        if not sides or sides[-1] != side:
            sides.append(side)
    return sides


def _passed_once(leaf: str, goal: Pose) -> Run:
    """Drive through the study door (its leaf as ``leaf`` adds to the door's entry) to
    ``goal``: there by the truth, through the door once, never back; the run."""
    world = World.from_yaml_text(_FLAT.format(leaf=leaf))
    run = build_run(RunSettings(world=world, seed=3, fidelity=Fidelity.EMBODIED))
    report = run.robot.move_to(goal)
    x, y, _ = run.simulation.robot_pose
    assert report.reached and math.dist((x, y), goal.xy()) < 0.3  # judged by the truth
    assert report.doors_passed == ("study door",)
    assert _sides(run.path()) == [-1, 1]  # through once, never back through the door
    return run


@pytest.mark.parametrize("goal", [Pose(4.8, 1.4, 0.0), Pose(4.2, 2.2, math.pi / 2)])
def test_a_narrow_doorway_is_passed_once(goal: Pose) -> None:
    _passed_once("", goal)


@pytest.mark.parametrize(("hinge", "into"), [("south", "study"), ("north", "hall")])
def test_a_half_open_doorway_is_passed_once_without_touching_the_leaf(hinge: str,
                                                                      into: str) -> None:
    run = _passed_once(f", opening: 60, hinge: {hinge}, swings_into: {into}",
                       Pose(4.6, 1.6, 0.0))
    assert run.simulation.collisions == []
