"""Sound in the simulated home: what the robot's speaker plays and its microphone hears.

``AudioScene`` is the simulation's audio log: every sound (the robot's voice, a person
speaking) is kept with the simulated time it started and who made it, and ``mix(start,
end)`` gives what a listener at the robot hears over that span, the sounds summed over a
seeded noise floor. ``SimSpeaker`` plays into it: the sound starts now, the body ticks
for its duration (time passes as the robot speaks), a ``sim.speech`` event records
the text and the seconds, and whoever listens (``homebot.sim.hearing``) hears it.
``SimMicrophone`` reads the scene from where it last stopped to the body's clock.
The scene keeps only numpy arrays (16 kHz mono int16); speech synthesis and recognition
live in ``homebot.speech``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from homebot.errors import BodyError
from homebot.events import EventLog
from homebot.robot import Microphone, Speaker

__all__ = ["AUDIO_RATE", "AudioScene", "SimMicrophone", "SimSpeaker", "Sound"]

AUDIO_RATE = 16_000
#: A microphone read returns at most this much of the past.
_MAX_READ_SECONDS = 30.0
#: Standard deviation of the room's noise floor, in int16 units (about -60 dBFS).
_NOISE_FLOOR = 30.0


@dataclass(frozen=True)
class Sound:
    """One sound in the home: its samples (int16 at ``AUDIO_RATE``), when it started
    (simulated seconds), who made it and, for speech, what it says."""

    start: float
    samples: np.ndarray
    source: str
    text: str | None = None

    @property
    def seconds(self) -> float:
        return self.samples.size / AUDIO_RATE

    @property
    def end(self) -> float:
        return self.start + self.seconds


class AudioScene:
    """The sounds of one simulation, on its clock (see the module docstring)."""

    def __init__(self, now: Callable[[], float], seed: int = 0) -> None:
        self._now = now
        self._seed = seed
        self.sounds: list[Sound] = []

    def emit(self, samples: np.ndarray, *, source: str, text: str | None = None,
             start: float | None = None) -> Sound:
        """Add a sound that starts at ``start`` (default: now)."""
        data = np.asarray(samples)
        if data.ndim != 1 or not np.issubdtype(data.dtype, np.integer):
            raise BodyError("a sound is one channel of 16-bit samples (a 1-d int16 array); "
                            f"got an array of shape {data.shape} and type {data.dtype}")
        sound = Sound(self._now() if start is None else start, data.astype(np.int16),
                      source, text)
        self.sounds.append(sound)
        return sound

    def mix(self, start: float, end: float) -> np.ndarray:
        """What is heard from ``start`` to ``end`` (simulated seconds): the noise floor
        (seeded by the span, so a span always sounds the same) and every sound in it."""
        first = round(start * AUDIO_RATE)
        length = max(0, round(end * AUDIO_RATE) - first)
        rng = np.random.default_rng([self._seed, max(0, first)])
        out = rng.normal(0.0, _NOISE_FLOOR, length)
        for sound in self.sounds:
            offset = round(sound.start * AUDIO_RATE) - first
            lo, hi = max(0, offset), min(length, offset + sound.samples.size)
            if lo < hi:
                out[lo:hi] += sound.samples[lo - offset:hi - offset]
        mixed: np.ndarray = np.clip(np.round(out), -32768, 32767).astype(np.int16)
        return mixed


class SimSpeaker(Speaker):
    """The robot's loudspeaker in the simulation: the sound goes into ``scene`` and the
    body ticks (``tick`` is ``SimBody.tick``, ``tick_period`` its seconds) for as long
    as it lasts."""

    def __init__(self, scene: AudioScene, events: EventLog, tick: Callable[[int], None],
                 tick_period: float, heard: Callable[[Sound], None] | None = None) -> None:
        self.rate = AUDIO_RATE
        self._scene, self._events = scene, events
        self._tick, self._tick_period = tick, tick_period
        self._heard = heard

    def play(self, samples: np.ndarray, *, text: str | None = None) -> float:
        sound = self._scene.emit(samples, source="robot", text=text)
        self._events.record("sim.speech", text=text or "", seconds=round(sound.seconds, 3),
                            start=round(sound.start, 3))
        self._tick(math.ceil(sound.seconds / self._tick_period - 1e-9))
        if self._heard is not None:  # the people who heard it react once it is said
            self._heard(sound)
        return sound.seconds


class SimMicrophone(Microphone):
    """The robot's microphone in the simulation: reads ``scene`` up to ``now()``."""

    def __init__(self, scene: AudioScene, now: Callable[[], float]) -> None:
        self.rate = AUDIO_RATE
        self._scene, self._now = scene, now
        self._read_until = now()

    def read(self) -> np.ndarray:
        end = self._now()
        start = max(self._read_until, end - _MAX_READ_SECONDS)
        self._read_until = end
        return self._scene.mix(start, end)
