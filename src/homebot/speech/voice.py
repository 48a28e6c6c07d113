"""The robot's voice: espeak-ng (bundled by ``espeakng-loader``) through a small ctypes wrapper.

espeak-ng's C library keeps one global synthesiser per process, so ``Voice`` holds the
loaded library and serialises every call with a lock. Audio comes back as 16-bit mono
samples at espeak-ng's own rate (22 050 Hz) and is resampled to the recogniser's 16 kHz.

Reproducible: the Klatt synthesiser keeps state in C statics from one utterance to the next
(its F0 flutter is three sines of a ``time_count`` that only grows, period 20 calls; the
output filter and echo buffer keep the last utterance's tail), so the same text in the
same voice came out differently on each call (5 different waveforms cycling for one
sentence; about 20 % of the signal's energy differs), and a benchmark's audio depended
on everything spoken before it in the process. ``espeak_ng_SetRandSeed``, libc ``srand``
and re-initialising do not reset that state. Where the platform can fork, each utterance
is therefore synthesised in a forked child of a process that never synthesises itself
(``homebot.speech.synthesis_process``, started once): every utterance starts from the same
state, so a text in a voice gives the same samples whatever was said before
(``reproducible=False`` synthesises in-process).
"""

from __future__ import annotations

import ctypes
import functools
import importlib.util
import json
import os
import struct
import subprocess
import sys
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from homebot.errors import SpeechError
from homebot.speech.audio import SAMPLE_RATE, resample
from homebot.speech.synthesis_process import NO_VOICE

__all__ = ["HELD_OUT_VOICES", "MAX_SPOKEN_CHARACTERS", "VOICES", "EspeakLibrary", "Voice",
           "VoiceSettings", "espeak", "in_process_voice"]

#: The longest text spoken at once: about two minutes of speech. Synthesis holds the whole
#: utterance in memory several times over (about 23 KB a character: 96 KB of text took
#: 2.25 GB), so a longer text is refused rather than spoken.
MAX_SPOKEN_CHARACTERS = 2_000

_AUDIO_OUTPUT_SYNCHRONOUS = 2
_CHARS_UTF8 = 1
_RATE, _VOLUME, _PITCH = 1, 2, 3
_IPA = 0x02

_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(ctypes.c_short), ctypes.c_int,
                             ctypes.c_void_p)


@dataclass(frozen=True, slots=True)
class VoiceSettings:
    """One way of speaking: an espeak-ng voice name (``en-us``, ``en+m3``...), words per
    minute and pitch (0-99)."""

    name: str = "en-us"
    rate: int = 160
    pitch: int = 50

    def label(self) -> str:
        return f"{self.name}@{self.rate}wpm"


# Voices and speeds the speech benchmark speaks with: espeak-ng's Klatt voices (US and
# British, four timbres, 115-150 words a minute). Its default formant voices are heard far
# worse by the en-US acoustic model (6 of 12 commands against 10 of 12 in a first check).
VOICES: tuple[VoiceSettings, ...] = (
    VoiceSettings("en-us+klatt", 125, 50),
    VoiceSettings("en-us+klatt4", 140, 60),
    VoiceSettings("en+klatt2", 115, 45),
    VoiceSettings("en-us+klatt3", 150, 40),
)
# Voices no setting was tuned on (``homebot bench speech --voices held-out``): two other
# Klatt timbres, one faster and one slower than any of ``VOICES``.
HELD_OUT_VOICES: tuple[VoiceSettings, ...] = (
    VoiceSettings("en+klatt5", 165, 50),
    VoiceSettings("en-us+klatt6", 110, 50),
)


_NO_EXTRA = SpeechError("text to speech needs the speech extra: pip install 'homebot[speech]'")


def _no_such_voice(settings: VoiceSettings) -> SpeechError:
    return SpeechError(f"espeak-ng has no voice '{settings.name}'; try en-us, en, en+m3 or "
                       "en-us+f3")


class EspeakLibrary:
    """espeak-ng's C library in this process (one global synthesiser, so one per process:
    ``in_process_voice()``); every call is serialised by a lock."""

    def __init__(self) -> None:
        try:
            import espeakng_loader
        except ImportError:
            raise _NO_EXTRA from None
        try:
            self._lib = ctypes.CDLL(espeakng_loader.get_library_path())
            data = espeakng_loader.get_data_path()
        except (OSError, RuntimeError) as error:  # pragma: no cover - broken install
            raise SpeechError(f"espeak-ng could not be loaded ({error}); reinstall the "
                              "speech extra: pip install --force-reinstall espeakng-loader"
                              ) from None
        lib = self._lib
        lib.espeak_Initialize.restype = ctypes.c_int
        lib.espeak_Initialize.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_char_p,
                                          ctypes.c_int]
        lib.espeak_SetVoiceByName.argtypes = [ctypes.c_char_p]
        lib.espeak_SetParameter.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int]
        lib.espeak_SetSynthCallback.argtypes = [_CALLBACK]
        lib.espeak_Synth.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint,
                                     ctypes.c_int, ctypes.c_uint, ctypes.c_uint,
                                     ctypes.c_void_p, ctypes.c_void_p]
        lib.espeak_TextToPhonemes.restype = ctypes.c_char_p
        lib.espeak_TextToPhonemes.argtypes = [ctypes.POINTER(ctypes.c_char_p), ctypes.c_int,
                                              ctypes.c_int]
        self.rate = int(lib.espeak_Initialize(_AUDIO_OUTPUT_SYNCHRONOUS, 0,
                                              data.encode(), 0))
        if self.rate <= 0:  # pragma: no cover - broken install
            raise SpeechError("espeak-ng did not start; reinstall the speech extra")
        self._chunks: list[NDArray[np.int16]] = []
        self._callback = _CALLBACK(self._collect)  # kept alive as long as the library uses it
        lib.espeak_SetSynthCallback(self._callback)
        self._lock = threading.Lock()

    def _collect(self, samples: Any, count: int, events: Any) -> int:
        if count > 0:
            self._chunks.append(np.ctypeslib.as_array(samples, shape=(count,)).copy())
        return 0

    def _use(self, settings: VoiceSettings) -> None:
        if self._lib.espeak_SetVoiceByName(settings.name.encode()) != 0:
            raise _no_such_voice(settings)
        self._lib.espeak_SetParameter(_RATE, max(80, min(450, settings.rate)), 0)
        self._lib.espeak_SetParameter(_PITCH, max(0, min(99, settings.pitch)), 0)

    def synthesise_native(self, text: str, settings: VoiceSettings) -> NDArray[np.int16]:
        """``text`` in ``settings`` at espeak-ng's own rate (``self.rate``)."""
        encoded = text.encode("utf-8") + b"\0"
        with self._lock:
            self._use(settings)
            self._chunks = []
            self._lib.espeak_Synth(encoded, len(encoded), 0, 0, 0, _CHARS_UTF8, None, None)
            self._lib.espeak_Synchronize()
            chunks, self._chunks = self._chunks, []
        return np.concatenate(chunks) if chunks else np.zeros(0, dtype=np.int16)

    def phonemes(self, word: str, settings: VoiceSettings) -> str:
        with self._lock:
            self._use(settings)
            pointer = ctypes.c_char_p(word.encode("utf-8"))
            parts = []
            while pointer.value:
                result = self._lib.espeak_TextToPhonemes(ctypes.byref(pointer), _CHARS_UTF8,
                                                         _IPA)
                if result:
                    parts.append(result.decode("utf-8"))
        return " ".join(parts)


@functools.cache
def in_process_voice() -> EspeakLibrary:
    """This process's one espeak-ng."""
    return EspeakLibrary()


class _SynthesisClient:
    """Talks to ``homebot.speech.synthesis_process``, started on first use."""

    def __init__(self) -> None:
        root = str(Path(__file__).resolve().parents[2])  # so the process imports this homebot
        path = os.pathsep.join(filter(None, (root, os.environ.get("PYTHONPATH"))))
        self._process = subprocess.Popen(
            [sys.executable, "-c", "from homebot.speech.synthesis_process import serve; serve()"],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE,
            env={**os.environ, "PYTHONPATH": path})
        self._lock = threading.Lock()
        self.rate = struct.unpack("<i", self._read(4))[0]

    def _read(self, size: int) -> bytes:
        assert self._process.stdout is not None
        data = self._process.stdout.read(size)
        if len(data) < size:
            raise SpeechError("the espeak-ng synthesis process stopped (status "
                              f"{self._process.poll()}); reinstall the speech extra: "
                              "pip install --force-reinstall espeakng-loader")
        return data

    def ask(self, op: str, text: str, settings: VoiceSettings) -> bytes:
        request = json.dumps({"op": op, "text": text, "name": settings.name,
                              "rate": settings.rate, "pitch": settings.pitch}).encode()
        assert self._process.stdin is not None
        with self._lock:
            try:
                self._process.stdin.write(struct.pack("<I", len(request)) + request)
                self._process.stdin.flush()
            except BrokenPipeError:
                self._read(1)  # raises the SpeechError saying the process stopped
            status, size = struct.unpack("<iI", self._read(8))
            data = self._read(size) if size else b""
        if os.WIFEXITED(status) and os.WEXITSTATUS(status) == NO_VOICE:
            raise _no_such_voice(settings)
        if status != 0:  # pragma: no cover - the child crashed
            raise SpeechError(f"espeak-ng failed to synthesise (status {status}); reinstall "
                              "the speech extra: pip install --force-reinstall espeakng-loader")
        return data


@functools.cache
def _synthesis_client() -> _SynthesisClient:
    return _SynthesisClient()


class Voice:
    """espeak-ng: ``synthesise(text, settings)`` returns 16 kHz int16 samples."""

    def __init__(self, *, reproducible: bool = hasattr(os, "fork")) -> None:
        self.reproducible = reproducible
        if importlib.util.find_spec("espeakng_loader") is None:
            raise _NO_EXTRA
        if not reproducible:
            in_process_voice()

    @property
    def rate(self) -> int:
        """espeak-ng's own sample rate (asking starts the synthesis process: a text refused
        before then costs nothing)."""
        return (_synthesis_client() if self.reproducible else in_process_voice()).rate

    def synthesise(self, text: str, settings: VoiceSettings = VoiceSettings()) -> NDArray[
            np.int16]:
        """``text`` spoken in ``settings``, as 16 kHz mono int16 samples."""
        if not text.strip():
            raise SpeechError("there is nothing to say: give some text")
        if len(text) > MAX_SPOKEN_CHARACTERS:
            raise SpeechError(f"a text of {len(text):,} characters is too long to say at once; "
                              f"the robot says at most {MAX_SPOKEN_CHARACTERS:,}: split it "
                              "into sentences")
        if self.reproducible:
            audio = np.frombuffer(_synthesis_client().ask("synthesise", text, settings),
                                  dtype=np.int16).copy()
        else:
            audio = in_process_voice().synthesise_native(text, settings)
        return resample(audio, self.rate, SAMPLE_RATE)

    def phonemes(self, word: str, settings: VoiceSettings = VoiceSettings()) -> str:
        """How espeak-ng pronounces ``word``, in IPA (used for words not in the dictionary)."""
        if self.reproducible:
            return _synthesis_client().ask("phonemes", word, settings).decode("utf-8")
        return in_process_voice().phonemes(word, settings)



@functools.cache
def espeak() -> Voice:
    """The process's one espeak-ng (its C library is a global synthesiser)."""
    return Voice()
