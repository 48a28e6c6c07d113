"""The embodied robot sees people with its laser and head camera, never by the truth's dice.

Each test moves or dresses people in the simulation and checks that what the
robot reports follows from what its sensors could show: a face named only from
near, a seated person behind a table seen by the camera, a visitor nameless.
"""

from __future__ import annotations

import math

import pytest

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.geometry import Pose
from homebot.navigation import Navigator
from homebot.robot import PersonPercept
from homebot.task import Step, Task
from homebot.world import World

pytest.importorskip("cv2")


def _run(world: World, navigator: Navigator) -> Run:
    return build_run(RunSettings(
        world=world, seed=0, navigator=navigator, fidelity=Fidelity.EMBODIED))


def _place_robot(run: Run, pose: Pose) -> None:
    run.simulation.robot_pose = (pose.x, pose.y, pose.theta)
    run.robot.localisation.initialise(pose, spread=0.01, angle_spread=0.01)  # type: ignore[attr-defined]


def _near(seen: list[PersonPercept], point: tuple[float, float],
          reach: float = 0.4) -> PersonPercept:
    close = [person for person in seen if math.dist(person.position, point) <= reach]
    assert len(close) == 1, seen
    return close[0]


def test_a_face_is_named_only_from_near_and_the_body_is_described(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    # Sophie stands behind the robot, 1.2 m away (nearer, her waving hand would be out of
    # the head camera's 58° beside her head)
    _place_robot(run, Pose(9.8, 8.6, 0.0))
    seen = run.robot.perceive_people()
    sophie = _near(seen, run.simulation.people["Sophie"].position)
    assert sophie.name == "Sophie"
    assert sophie.posture == "standing"
    assert sophie.gesture == "waving"
    assert sophie.clothes[0] == "yellow top"
    assert sophie.room == "office"
    # from across the room she is seen, but her face is too small to name her
    run.simulation.move_person("Sophie", (11.3, 8.9))
    _place_robot(run, Pose(8.3, 6.6, 0.0))
    far = _near(run.robot.perceive_people(), (11.3, 8.9))
    assert far.name is None
    assert far.posture == "standing"


def test_a_seated_person_behind_a_table_is_seen_by_the_camera_not_the_laser(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    _place_robot(run, Pose(11.0, 1.0, math.pi))
    run.simulation.move_person("Maria", (7.8, 2.9))  # sitting, beyond the kitchen table
    maria = _near(run.robot.perceive_people(), (7.8, 2.9), reach=0.5)
    assert maria.posture == "sitting"
    assert maria.gesture == "raising_left_arm"
    assert maria.clothes == ("red top",)
    assert maria.name is None  # 3.7 m away


def test_someone_lying_on_the_bed_is_seen_lying_and_other_rooms_are_not_looked_into(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    _place_robot(run, Pose(2.6, 7.6, math.pi))
    seen = run.robot.perceive_people()
    assert [person.room for person in seen] == ["bedroom"]
    john = _near(seen, run.simulation.people["John"].position, reach=0.5)
    assert john.posture == "lying"


def test_a_visitor_is_seen_but_never_named_until_they_say_their_name(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    _place_robot(run, Pose(9.5, 8.0, 0.0))
    run.simulation.move_person("Sophie", (4.5, 1.2))  # out of the office
    visitor = run.simulation.place_person_in_doorway("office door")
    door = apartment.doors["office door"].position
    _place_robot(run, Pose(door[0], door[1] + 1.0, -math.pi / 2))
    stranger = _near(run.robot.perceive_people(), run.simulation.people[visitor].position)
    assert stranger.name is None


def test_find_person_goes_up_to_someone_too_far_to_recognise(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.move_person("Sophie", (11.3, 8.9))
    report = run.run(Task((Step("find_person", {"person": "Sophie", "room": "office"}),)))
    assert report.success
    assert math.dist(run.simulation.robot_pose[:2], (11.3, 8.9)) < 2.0
    assert run.simulation.collisions == []


def test_each_robot_enrols_newcomers_in_its_own_copy_of_the_household(apartment: World) -> None:
    import numpy as np

    from homebot.app.perception import household_faces
    from homebot.sim.faces import face_identity, face_view

    first, second = household_faces(apartment), household_faces(apartment)
    household = sorted(person.name for person in apartment.model.people)
    assert sorted(first.people) == household
    rng = np.random.default_rng(3)
    first.enrol("Zoe", [face_view(face_identity("Zoe"), rng)[0] for _ in range(8)])
    assert "Zoe" in first.people
    assert sorted(second.people) == household == sorted(household_faces(apartment).people)
