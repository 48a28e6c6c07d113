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
is therefore synthesised in a forked child of this process, which never synthesises
itself: every utterance starts from the same state, so a text in a voice gives the same
samples whatever was said before (``reproducible=False`` synthesises in-process).
"""

from __future__ import annotations

import ctypes
import functools
import os
import threading
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from homebot.errors import SpeechError
from homebot.speech.audio import SAMPLE_RATE, resample

__all__ = ["HELD_OUT_VOICES", "VOICES", "Voice", "VoiceSettings", "espeak"]

_AUDIO_OUTPUT_SYNCHRONOUS = 2
_CHARS_UTF8 = 1
_RATE, _VOLUME, _PITCH = 1, 2, 3
_NO_VOICE = 3  # a child's exit status: espeak-ng has no such voice
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


class Voice:
    """espeak-ng, loaded once: ``synthesise(text, settings)`` returns 16 kHz int16 samples."""

    def __init__(self, *, reproducible: bool = hasattr(os, "fork")) -> None:
        self.reproducible = reproducible
        try:
            import espeakng_loader
        except ImportError:
            raise SpeechError("text to speech needs the speech extra: "
                              "pip install 'homebot[speech]'") from None
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
            raise SpeechError(f"espeak-ng has no voice '{settings.name}'; try en-us, en, "
                              "en+m3 or en-us+f3")
        self._lib.espeak_SetParameter(_RATE, max(80, min(450, settings.rate)), 0)
        self._lib.espeak_SetParameter(_PITCH, max(0, min(99, settings.pitch)), 0)

    def synthesise(self, text: str, settings: VoiceSettings = VoiceSettings()) -> NDArray[
            np.int16]:
        """``text`` spoken in ``settings``, as 16 kHz mono int16 samples."""
        if not text.strip():
            raise SpeechError("there is nothing to say: give some text")
        encoded = text.encode("utf-8") + b"\0"
        with self._lock:
            if self.reproducible:
                audio = self._synthesise_in_child(encoded, settings)
            else:
                audio = self._synthesise_here(encoded, settings)
        return resample(audio, self.rate, SAMPLE_RATE)

    def _synthesise_here(self, encoded: bytes, settings: VoiceSettings) -> NDArray[np.int16]:
        self._use(settings)
        self._chunks = []
        self._lib.espeak_Synth(encoded, len(encoded), 0, 0, 0, _CHARS_UTF8, None, None)
        self._lib.espeak_Synchronize()
        chunks, self._chunks = self._chunks, []
        return np.concatenate(chunks) if chunks else np.zeros(0, dtype=np.int16)

    def _synthesise_in_child(self, encoded: bytes, settings: VoiceSettings
                             ) -> NDArray[np.int16]:
        """Synthesise in a forked child (see the module docstring) and read its samples
        through a pipe. The child chooses the voice, synthesises and writes: this process
        leaves espeak-ng's state alone (choosing voices over and over without speaking
        made a child crash after 83 utterances)."""
        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:  # pragma: no cover - runs in the child, which exits at once
            status = 1
            try:
                os.close(read)
                data = self._synthesise_here(encoded, settings).tobytes()
                view = memoryview(data)
                while view:
                    view = view[os.write(write, view):]
                status = 0
            except SpeechError:
                status = _NO_VOICE
            finally:
                os._exit(status)
        os.close(write)
        with os.fdopen(read, "rb") as handle:
            data = handle.read()
        _, status = os.waitpid(pid, 0)
        if os.WIFEXITED(status) and os.WEXITSTATUS(status) == _NO_VOICE:
            self._use(settings)  # raises the SpeechError naming the voice
        if status != 0:  # pragma: no cover - the child crashed
            raise SpeechError(f"espeak-ng failed to synthesise (status {status}); reinstall "
                              "the speech extra: pip install --force-reinstall espeakng-loader")
        return np.frombuffer(data, dtype=np.int16).copy()

    def phonemes(self, word: str, settings: VoiceSettings = VoiceSettings()) -> str:
        """How espeak-ng pronounces ``word``, in IPA (used for words not in the dictionary)."""
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
def espeak() -> Voice:
    """The process's one espeak-ng (its C library is a global synthesiser)."""
    return Voice()
