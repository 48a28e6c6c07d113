"""The robot checks what it heard ("Did you say ...?") and asks again on a no; the
simulated person says yes only when the robot repeated the words of their answer. The
truth (what the responder answered) is read only by the tests, to judge."""

from __future__ import annotations

import pytest

pytest.importorskip("cv2")
pytest.importorskip("pocketsphinx")
pytest.importorskip("espeakng_loader")

from homebot.app import Fidelity, Run, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.sim import ScriptedResponder
from homebot.speech.grammar import words_of
from homebot.world import World


def _run_beside(world: World, navigator: Navigator, person: str) -> Run:
    run = build_run(RunSettings(world=world, seed=5, navigator=navigator,
                                fidelity=Fidelity.EMBODIED))
    sim = run.simulation
    x, y, _ = sim.robot_pose
    sim.move_person(person, sim.free_floor_near((x + 1.0, y)))
    return run


def _exchange(run: Run) -> list[tuple[str, str]]:
    """(who, what) of every utterance, the robot's and the people's, in order."""
    return [("robot", e.data["text"]) if e.kind == "sim.speech" else
            (e.data["person"], e.data["text"])
            for e in run.simulation.events.events
            if e.kind in ("sim.speech", "sim.person_said")]


def test_an_answer_about_oneself_is_heard_and_confirmed(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run_beside(apartment, apartment_navigator, "Sophie")
    truth = run.simulation.responder(run.simulation.people["Sophie"].model,
                                     "where are you from?")
    assert truth == "Lyon"
    answer = run.robot.ask("Sophie", "Where are you from?")
    assert answer is not None and "lyon" in words_of(answer)
    said = _exchange(run)
    assert ("Sophie", "Lyon") in said or ("Sophie", "I said Lyon.") in said
    assert said[-2][0] == "robot" and said[-2][1].startswith("Did you say")
    assert said[-1] == ("Sophie", "Yes.")


def test_a_visitors_name_misheard_as_a_household_name_is_denied_not_taken(
        apartment: World, apartment_navigator: Navigator) -> None:
    run = _run_beside(apartment, apartment_navigator, "Sophie")
    run.simulation.responder = ScriptedResponder({"Sophie": {"what is your name": "Olivia"}})
    answer = run.robot.ask("Sophie", "What is your name?")
    assert answer is None or "olivia" in words_of(answer)  # never a wrong name
    said = _exchange(run)
    for index, (who, text) in enumerate(said[:-1]):
        if who == "robot" and text.startswith("Did you say"):
            right = "olivia" in words_of(text)
            assert said[index + 1] == ("Sophie", "Yes." if right else "No.")
