"""The simulation's sound: the speaker plays into the audio scene and takes its duration of
simulated time; the microphone hears the scene since its last read."""

from __future__ import annotations

import numpy as np
import pytest

from homebot.errors import BodyError
from homebot.navigation import Navigator
from homebot.sim import Simulation
from homebot.sim.audio import AUDIO_RATE, AudioScene
from homebot.sim.body import SimBody
from homebot.world import World


def _tone(seconds: float, amplitude: float = 8000.0) -> np.ndarray:
    t = np.arange(round(seconds * AUDIO_RATE)) / AUDIO_RATE
    return np.round(amplitude * np.sin(2 * np.pi * 440.0 * t)).astype(np.int16)


def test_the_speaker_takes_the_sounds_duration_and_the_log_keeps_it(
        apartment: World, apartment_navigator: Navigator) -> None:
    sim = Simulation(apartment, seed=3, navigator=apartment_navigator)
    body = SimBody(sim)
    start = body.now()
    seconds = body.speaker().play(_tone(1.23), text="la")
    assert seconds == pytest.approx(1.23)
    # the body ticked while it played: the clock ran the sound's length, to a tick
    assert 1.23 <= body.now() - start < 1.23 + body.tick_period + 1e-9
    (sound,) = body.audio.sounds
    assert (sound.source, sound.text, sound.start) == ("robot", "la", start)
    speech = [event for event in sim.events.events if event.kind == "sim.speech"]
    assert speech[-1].data["text"] == "la"
    assert speech[-1].data["seconds"] == pytest.approx(1.23)


def test_the_microphone_hears_the_scene_since_its_last_read(
        apartment: World, apartment_navigator: Navigator) -> None:
    body = SimBody(Simulation(apartment, seed=3, navigator=apartment_navigator))
    microphone = body.microphone()
    body.tick(10)
    quiet = microphone.read()
    assert quiet.size == round(10 * body.tick_period * AUDIO_RATE)
    assert float(np.std(quiet)) < 100.0  # the room's noise floor only
    body.audio.emit(_tone(0.2), source="alex", text="hello")
    body.tick(10)
    heard = microphone.read().astype(np.float64)
    loud = np.abs(heard) > 1000
    # the tone, from when it started, for 0.2 s; nothing before the read began again
    assert loud[:round(0.2 * AUDIO_RATE) - 50].mean() > 0.5
    assert not loud[round(0.2 * AUDIO_RATE) + 10:].any()
    assert microphone.read().size == 0  # no time passed


def test_a_span_always_sounds_the_same_and_bad_sounds_are_refused() -> None:
    now = [0.0]
    scene = AudioScene(lambda: now[0], seed=1)
    scene.emit(_tone(0.5), source="robot", start=0.25)
    assert np.array_equal(scene.mix(0.0, 1.0), scene.mix(0.0, 1.0))
    assert scene.mix(0.0, 1.0).size == AUDIO_RATE
    with pytest.raises(BodyError, match="1-d int16"):
        scene.emit(np.zeros((10, 2), dtype=np.int16), source="alex")
    with pytest.raises(BodyError, match="1-d int16"):
        scene.emit(np.zeros(10), source="alex")
