"""The embodied robot speaks through its body's speaker: espeak-ng's audio goes into the
simulation's sound, taking its duration, and a listener at the robot hears the words."""

from __future__ import annotations

import random

import pytest

from homebot.app import Fidelity, RunSettings, build_run
from homebot.navigation import Navigator
from homebot.world import World

pytest.importorskip("cv2")
pytest.importorskip("pocketsphinx")
pytest.importorskip("espeakng_loader")

from homebot.speech import Recognizer, yes_no_grammar


def test_the_robot_says_it_aloud_and_is_heard(apartment: World,
                                              apartment_navigator: Navigator) -> None:
    run = build_run(RunSettings(
        world=apartment, seed=0, navigator=apartment_navigator, fidelity=Fidelity.EMBODIED))
    body = run.robot.body  # type: ignore[attr-defined]
    microphone = body.microphone()
    start = run.simulation.clock.now()
    run.robot.say("yes please")
    (sound,) = body.audio.sounds
    assert sound.source == "robot" and sound.text == "yes please"
    assert 0.5 < sound.seconds < 3.0
    # simulated time ran for as long as the robot spoke, to a tick
    elapsed = run.simulation.clock.now() - start
    assert sound.seconds <= elapsed < sound.seconds + body.tick_period + 1e-9
    body.tick(10)  # a moment of quiet after it
    grammar = yes_no_grammar()
    listener = Recognizer({"yes_no": grammar},
                          {"yes_no": grammar.sample(random.Random(0), 200)})
    assert listener.hear(microphone.read(), "yes_no").text == "yes please"
