"""Online enrolment: "my name is ..." said in front of the embodied robot enrols the face."""

from __future__ import annotations

import math

import numpy as np
import pytest

from homebot.perception.faces import Acquaintances, FaceDetector, FaceMemory, introduced_name
from homebot.sim.faces import face_identity, face_view


@pytest.mark.parametrize(("utterance", "name"), [
    ("my name is maria", "Maria"), ("Hello, my name is Anna Maria.", "Anna Maria"),
    ("I'm Adel", "Adel"), ("call me Sam, please", "Sam"), ("I am thirsty", None),
    ("bring me a coke", None), ("I'm looking for the kitchen", None)])
def test_the_name_a_person_gives(utterance: str, name: str | None) -> None:
    assert introduced_name(utterance) == name


def test_acquaintances_enrol_on_an_introduction_only(detector: FaceDetector) -> None:
    made: list[FaceMemory] = []

    def memory() -> FaceMemory:
        made.append(FaceMemory(detector, trees=40, features=600))
        return made[-1]

    met = Acquaintances(memory)
    rng = np.random.default_rng(7)
    views = [face_view(face_identity("someone"), rng)[0] for _ in range(8)]
    assert met.recognise(views) is None and not made  # nobody met: nothing trained
    assert met.introduce("bring me a coke", views) is None and not made
    assert met.introduce("my name is Zoe", views) == "Zoe"
    assert met.people == ["Zoe"] and len(made) == 1


def test_a_person_who_says_my_name_is_in_front_of_the_embodied_robot_is_recognised(
        detector: FaceDetector) -> None:
    pytest.importorskip("cv2")
    from homebot.app.embodied import embodied_robot_in
    from homebot.embodied import BodyRobot
    from homebot.navigation import Navigator
    from homebot.sim import Simulation
    from homebot.world import World

    world = World.load("apartment")
    sim = Simulation(world, navigator=Navigator(world), seed=3)
    robot = embodied_robot_in(sim, Navigator(world))
    assert isinstance(robot, BodyRobot)
    assert robot.acquaintances is not None
    # the wiring trains its detector on first use; a small one keeps the test quick
    robot.acquaintances = Acquaintances(lambda: FaceMemory(detector, trees=60, features=800))
    x, y, theta = sim.robot_pose
    other = next(name for name in sorted(sim.people) if name != "Alex")

    def stand_in_front(name: str) -> None:
        for index, someone in enumerate(sim.people):  # everyone else well out of view
            if someone != name:
                sim.people[someone].position = (x - 3 * math.cos(theta) + 0.01 * index,
                                              y - 3 * math.sin(theta))
        sim.people[name].position = (x + 1.2 * math.cos(theta), y + 1.2 * math.sin(theta))

    assert robot.introduce("my name is Zoe") is None  # nobody in front
    stand_in_front("Alex")
    assert robot.face_in_front() is None  # nobody met yet
    assert robot.introduce("Hello robot, my name is Zoe") == "Zoe"
    stand_in_front(other)
    assert robot.introduce("I'm Kim") == "Kim"
    # later looks: new views, new pose and light. A look may come out unknown (the
    # robot then looks again), never as the other person
    for name, person in (("Zoe", "Alex"), ("Kim", other)):
        stand_in_front(person)
        looks = [robot.face_in_front() for _ in range(5)]
        assert set(looks) <= {name, None} and looks.count(name) >= 3, (name, looks)
    assert [event.data["person"] for event in sim.events.of_kind("robot.met")] == \
        ["Zoe", "Kim"]
