"""Cutting audio into utterances with voice activity detection (pocketsphinx's WebRTC VAD).

Each 30 ms frame is judged speech or not by ``pocketsphinx.Vad``; a window of frames
(``window`` seconds) turns speech on when ``ratio`` of it is speech and off when
``ratio`` of it is not, as pocketsphinx's ``Endpointer`` does. Speech runs closer than
``gap`` seconds are one utterance (a command has short pauses between its words);
runs shorter than ``min_speech`` seconds are clicks and are dropped. Each utterance
keeps ``margin`` seconds of audio either side, so the decoders see its edges.
"""

from __future__ import annotations

from dataclasses import dataclass

from homebot.speech.audio import SAMPLE_RATE, Audio

__all__ = ["Segmenter", "Utterance"]


@dataclass(frozen=True, slots=True)
class Utterance:
    """One stretch of speech: sample positions in the audio it was cut from."""

    start: int
    end: int

    @property
    def seconds(self) -> float:
        return (self.end - self.start) / SAMPLE_RATE

    def of(self, audio: Audio) -> Audio:
        return audio[self.start:self.end]


@dataclass(frozen=True)
class Segmenter:
    """Voice activity detection and utterance segmentation (see the module docstring)."""

    mode: int = 1
    window: float = 0.3
    ratio: float = 0.7
    gap: float = 0.8
    min_speech: float = 0.3
    margin: float = 0.3

    def speech_frames(self, audio: Audio) -> tuple[list[bool], int]:
        """Per-frame VAD decisions and the frame length in samples."""
        from pocketsphinx import Vad

        vad = Vad(self.mode, SAMPLE_RATE)
        step = vad.frame_bytes // 2
        data = audio.astype("<i2").tobytes()
        decisions = [bool(vad.is_speech(data[start * 2:(start + step) * 2]))
                     for start in range(0, audio.size - step + 1, step)]
        return decisions, step

    def utterances(self, audio: Audio) -> list[Utterance]:
        """The utterances in ``audio``, in order (none in silence or steady noise-free hum)."""
        decisions, step = self.speech_frames(audio)
        width = max(1, round(self.window * SAMPLE_RATE / step))
        runs: list[list[int]] = []
        speaking = False
        for index in range(len(decisions)):
            recent = decisions[max(0, index - width + 1):index + 1]
            share = sum(recent) / width
            if not speaking and share >= self.ratio:
                speaking = True
                runs.append([max(0, index - width + 1), index + 1])
            elif speaking and (1 - share) >= self.ratio:
                speaking = False
            if speaking:
                runs[-1][1] = index + 1
        merged: list[list[int]] = []
        gap = self.gap * SAMPLE_RATE / step
        for run in runs:
            if merged and run[0] - merged[-1][1] <= gap:
                merged[-1][1] = run[1]
            else:
                merged.append(list(run))
        margin = int(self.margin * SAMPLE_RATE)
        return [Utterance(max(0, first * step - margin), min(audio.size, last * step + margin))
                for first, last in merged
                if (last - first) * step >= self.min_speech * SAMPLE_RATE]
