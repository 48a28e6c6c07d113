"""The embodied robot's hands and voice in a task, through its body only.

A person takes what the robot holds out only when it was offered to them, by pulling
at it (the robot lets go on the pull it feels at the wrist); a person asked puts what
they hold into the robot's open hand; a question is answered aloud and heard through the
microphone. The truth is read only by the tests, to judge.
"""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")
pytest.importorskip("pocketsphinx")
pytest.importorskip("espeakng_loader")

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.embodied.hands import ArmedBodyRobot
from homebot.navigation import Navigator
from homebot.sim import PERSON_PREFIX
from homebot.task import Step, Task
from homebot.world import World


def _run(world: World, navigator: Navigator, seed: int = 3) -> Run:
    return build_run(RunSettings(world=world, seed=seed, navigator=navigator,
                                 fidelity=Fidelity.EMBODIED))


def _fetch(obj: str, person: str, *, give: bool) -> Task:
    placement = str(World.load("apartment").objects[obj].placement)
    steps = [Step("navigate", {"to": placement}),
             Step("find_object", {"object": obj, "placement": placement}),
             Step("pick", {"object": obj}), Step("navigate", {"to": person})]
    return Task(tuple([*steps, Step("give", {"person": person})] if give else steps))


def test_the_robot_lets_go_only_when_the_person_it_offers_the_object_to_pulls(
        apartment: World, apartment_navigator: Navigator) -> None:
    obj = "teddy bear"
    # Held out without a word to anyone: nobody pulls, the robot keeps it.
    run = _run(apartment, apartment_navigator)
    assert run.run(_fetch(obj, "Sophie", give=False)).success
    robot = run.robot
    assert isinstance(robot, ArmedBodyRobot)
    hand = next(h for h, held in run.simulation.hands.items() if held == obj)
    assert not robot.hand_over(hand, "Sophie")
    assert run.simulation.hands[hand] == obj
    # Given ("Sophie, here is the teddy bear."): she pulls, the wrist feels it, the
    # fingers open; she has it.
    run = _run(apartment, apartment_navigator)
    assert run.run(_fetch(obj, "Sophie", give=True)).success
    assert run.simulation.object_location[obj] == PERSON_PREFIX + "Sophie"
    took = [e for e in run.simulation.events.events if e.kind == "sim.person"][-1]
    released = [e for e in run.simulation.events.events if e.kind == "robot.hand_over"][-1]
    assert took.data["did"] == "took" and released.data["released"]


def test_a_person_asked_puts_what_they_hold_into_the_open_hand(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    run.simulation.object_location["cola"] = PERSON_PREFIX + "Maria"
    report = run.run(Task((Step("navigate", {"to": "Maria"}),
                           Step("receive", {"person": "Maria", "object": "cola"}))))
    assert report.success, report.reason
    assert run.simulation.object_location["cola"].startswith("hand:")


def test_a_question_is_answered_aloud_and_heard_through_the_microphone(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    assert run.run(Task((Step("navigate", {"to": "Sophie"}),))).success
    robot = run.robot
    heard = robot.ask("Sophie", "what is your name?")
    assert heard is not None and "sophie" in heard
    said = [e.data for e in run.simulation.events.events if e.kind == "sim.person_said"]
    # she said it aloud (her name, maybe in a sentence), and that the robot heard it right
    assert said[-2]["person"] == "Sophie" and "Sophie" in said[-2]["text"]
    assert said[-1] == {"person": "Sophie", "text": "Yes."}
    # Nobody scripted an answer to this: silence, asked twice, then no answer.
    before = sum(e.kind == "sim.speech" for e in run.simulation.events.events)
    assert robot.ask("Sophie", "what is the colour of your car?") is None
    asked = [e.data["text"] for e in run.simulation.events.events
             if e.kind == "sim.speech"][before:]
    assert asked == ["Sophie, what is the colour of your car?"] * 2


def test_nobody_out_of_earshot_answers(apartment: World,
                                       apartment_navigator: Navigator) -> None:
    run = _run(apartment, apartment_navigator)
    robot = run.robot
    far = min(run.simulation.people.values(),
              key=lambda state: -abs(state.position[0] - run.simulation.robot_pose[0]))
    assert robot.ask(far.model.name, "what is your name?") is None
    assert not any(e.kind == "sim.person_said" for e in run.simulation.events.events)


def test_a_round_thing_put_in_the_hand_is_carried_and_put_on_a_high_surface(
        apartment: World, apartment_navigator: Navigator) -> None:
    # Held level as it was handed over (not swung down to the tucked pose, where a sphere
    # squeezes out between the pads), and put down with the torso raised so the elbow
    # clears the 0.8 m coat rack.
    run = _run(apartment, apartment_navigator)
    run.simulation.object_location["lemon"] = PERSON_PREFIX + "Maria"
    report = run.run(Task((Step("navigate", {"to": "Maria"}),
                           Step("receive", {"person": "Maria", "object": "lemon"}),
                           Step("navigate", {"to": "coat rack"}),
                           Step("place", {"placement": "coat rack", "object": "lemon"}))))
    assert report.success, report.reason
    assert run.simulation.object_location["lemon"] == "coat rack"
