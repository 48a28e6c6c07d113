"""A door leaf left barely ajar is told from someone standing in the doorway: the beams
pass its gap (the doorway reads open) but no way through is left, and the robot is to have
the door opened rather than ask people to step aside. Sweeps cast in
``test_door_seen_open_homes``'s small plan; then the embodied robot in a two-room flat."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import LineString, Point
from test_door_seen_open_homes import _CENTRE, _NORMAL, _WIDTH, _leaf, _sweep

from homebot.embodied.doors import door_seen_open, leaf_barely_ajar, way_through
from homebot.geometry import Pose, from_frame

_RADIUS = 0.25
_FACING = Pose(0.0, -0.6, math.pi / 2)  # stopped 0.6 m before the door, facing it
_ASKANCE = Pose(0.5, -0.9, 2.1)


def _leaf_hinged_right_towards_the_robot(opening_deg: float) -> object:
    angle = math.radians(opening_deg)
    hinge = (_WIDTH / 2, 0.0)
    tip = (hinge[0] - _WIDTH * math.cos(angle), hinge[1] - _WIDTH * math.sin(angle))
    return LineString([hinge, tip]).buffer(0.02)


def _ajar(pose: Pose, *extra: object) -> bool:
    points = from_frame(pose, _sweep(pose, *extra).points())
    return leaf_barely_ajar(points, _CENTRE, _NORMAL, _WIDTH, _RADIUS)


@pytest.mark.parametrize("pose", [_FACING, _ASKANCE])
@pytest.mark.parametrize("opening_deg", [10.0, 15.0, 25.0])
def test_a_leaf_barely_ajar_is_seen_as_one(pose: Pose, opening_deg: float) -> None:
    leaf = _leaf(opening_deg)
    # the old confusion: the doorway reads open, and no way through is left
    assert door_seen_open(_sweep(pose, leaf), pose, _CENTRE, _NORMAL, _WIDTH) is True
    points = from_frame(pose, _sweep(pose, leaf).points())
    assert way_through(points, _CENTRE, _NORMAL, _WIDTH, 0.1, _RADIUS) is None
    assert _ajar(pose, leaf)


@pytest.mark.parametrize("opening_deg", [15.0, 25.0])
def test_a_leaf_barely_ajar_towards_the_robot_from_the_other_jamb(opening_deg: float) -> None:
    assert _ajar(_FACING, _leaf_hinged_right_towards_the_robot(opening_deg))


@pytest.mark.parametrize("opening_deg", [55.0, 60.0, 75.0, 90.0])
def test_a_leaf_well_open_is_not_barely_ajar(opening_deg: float) -> None:
    assert not _ajar(_FACING, _leaf(opening_deg))
    assert not _ajar(_FACING, _leaf_hinged_right_towards_the_robot(opening_deg))


def test_an_open_doorway_is_not_a_leaf() -> None:
    assert not _ajar(_FACING)


@pytest.mark.parametrize("pose", [_FACING, _ASKANCE])
def test_someone_standing_in_the_doorway_is_no_leaf(pose: Pose) -> None:
    legs = [Point(-0.1, 0.0).buffer(0.06), Point(0.12, 0.02).buffer(0.06)]
    body = [Point(0.05, 0.05).buffer(0.2)]
    assert not _ajar(pose, *legs)
    assert not _ajar(pose, *body)
    # by the hinge of a leaf well open, someone standing in the gap: still no leaf ajar
    assert not _ajar(pose, _leaf(60.0), *legs)


_FLAT = """
name: study_door_barely_ajar
rooms:
  - {name: hall, polygon: [[0, 0], [3, 0], [3, 3], [0, 3]]}
  - {name: study, polygon: [[3, 0], [6, 0], [6, 3], [3, 3]]}
doors:
  - {name: study door, rooms: [hall, study], position: [3, 1.0], width: 0.8, opening: 15,
     hinge: south, swings_into: study}
categories:
  - {name: book, plural: books}
placements:
  - {name: desk, category: table, room: study, center: [5.4, 2.6], size: [1.0, 0.6],
     holds: [book]}
objects:
  - {name: atlas, category: book, placement: desk}
people:
  - {name: Ada, room: hall, position: [2.2, 2.4]}
operator: Ada
robot:
  pose: [1.0, 1.0, 0.0]
  radius: 0.25
"""


def test_the_robot_has_a_door_barely_ajar_opened_and_goes_through() -> None:
    pytest.importorskip("pocketsphinx")
    from homebot.app import Fidelity, RunSettings, build_run
    from homebot.task import Step, Task
    from homebot.world import World

    world = World.from_yaml_text(_FLAT)
    run = build_run(RunSettings(world=world, seed=3, fidelity=Fidelity.EMBODIED,
                                time_limit=240.0))
    blocked: list[str] = []
    asked: list[str] = []
    run.simulation.events.listeners.append(
        lambda event: blocked.append(str(event.data.get("blocker")))
        if event.kind == "robot.blocked" else asked.append(str(event.data.get("did")))
        if event.kind == "sim.person" else None)
    report = run.run(Task((Step("navigate", {"to": "desk"}),), "go to the desk"))
    # judged by the truth: in the study, through the door Ada opened wide when asked
    assert run.simulation.robot_room() == "study", report
    assert blocked and set(blocked) == {"door_closed"}  # never "someone in the doorway"
    assert "opened" in asked and "stepped aside" not in asked
    assert run.simulation.collisions == []
