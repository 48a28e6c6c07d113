"""Audio as numpy: WAV in and out (checked), resampling, and noise at a chosen SNR.

Everything the recogniser hears is 16 kHz mono int16, the rate of pocketsphinx's en-US
model. Other rates are resampled (``scipy.signal.resample_poly``); several channels are
averaged. An empty file, a file that is not WAV, a compressed WAV or one longer than
``MAX_SECONDS`` is refused with a ``SpeechError`` that says what to do.
"""

from __future__ import annotations

import io
import math
import wave
from fractions import Fraction
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.signal import resample_poly

from homebot.errors import SpeechError
from homebot.files import read_bytes_file

__all__ = ["MAX_SECONDS", "SAMPLE_RATE", "Audio", "add_noise", "babble", "denoise", "read_wav",
           "resample", "tones", "wav_bytes", "write_wav"]

SAMPLE_RATE = 16_000
# A spoken command lasts seconds; a recording longer than this is not one utterance.
MAX_SECONDS = 120.0
_MIN_RATE, _MAX_RATE = 4_000, 192_000

Audio = NDArray[np.int16]


def resample(samples: NDArray[np.int16], rate: int, target: int = SAMPLE_RATE) -> Audio:
    """``samples`` at ``rate`` Hz, resampled to ``target`` Hz (polyphase filter)."""
    if rate == target or samples.size == 0:
        return samples.astype(np.int16, copy=False)
    ratio = Fraction(target, rate).limit_denominator(1000)
    out = resample_poly(samples.astype(np.float64), ratio.numerator, ratio.denominator)
    return np.clip(np.round(out), -32768, 32767).astype(np.int16)


def read_wav(source: str | Path | bytes, *, name: str | None = None,
             max_seconds: float = MAX_SECONDS) -> Audio:
    """A WAV file (a path, or its bytes) as 16 kHz mono int16 samples.

    Raises ``SpeechError`` naming the file when it is missing, empty, not a PCM WAV, at a
    rate outside 4-192 kHz, silent of samples, or longer than ``max_seconds``.
    """
    label = name or (str(source) if not isinstance(source, bytes) else "<stdin>")
    if isinstance(source, bytes):
        data = source
    else:
        data = read_bytes_file(source, SpeechError, "audio", "WAV file")
    if not data:
        raise SpeechError(f"{label}: the file is empty; record a command as a 16-bit WAV")
    if data[:4] != b"RIFF" or data[8:12] != b"WAVE":
        raise SpeechError(f"{label}: not a WAV file; convert it, e.g. "
                          "ffmpeg -i IN -ar 16000 -ac 1 OUT.wav")
    try:
        with wave.open(io.BytesIO(data), "rb") as reader:
            channels, width = reader.getnchannels(), reader.getsampwidth()
            rate, frames = reader.getframerate(), reader.getnframes()
            if not _MIN_RATE <= rate <= _MAX_RATE:
                raise SpeechError(f"{label}: sample rate {rate} Hz; give 8-48 kHz audio "
                                  "(16 kHz is heard without resampling)")
            if frames / rate > max_seconds:
                raise SpeechError(f"{label}: {frames / rate:.0f} s long; a command is at most "
                                  f"{max_seconds:.0f} s: cut out the utterance")
            raw = reader.readframes(frames)
            if len(raw) < frames * channels * width:
                raise SpeechError(f"{label}: the WAV ends after {len(raw)} of the "
                                  f"{frames * channels * width} bytes of samples its header "
                                  "declares (cut short?); record or copy it again")
    except (wave.Error, EOFError) as error:
        raise SpeechError(f"{label}: not a PCM WAV file ({error}); convert it, e.g. "
                          "ffmpeg -i IN -ar 16000 -ac 1 -c:a pcm_s16le OUT.wav") from None
    samples = _to_int16(raw, width, label)
    if channels > 1:
        usable = samples.size - samples.size % channels
        samples = samples[:usable].reshape(-1, channels).mean(axis=1).astype(np.int16)
    if samples.size == 0:
        raise SpeechError(f"{label}: the WAV holds no samples; record a command")
    return resample(samples, rate)


def _to_int16(raw: bytes, width: int, label: str) -> Audio:
    if width == 2:
        return np.frombuffer(raw[: len(raw) - len(raw) % 2], dtype="<i2").astype(np.int16)
    if width == 1:
        return ((np.frombuffer(raw, dtype=np.uint8).astype(np.int16) - 128) * 256).astype(
            np.int16)
    if width == 4:
        wide = np.frombuffer(raw[: len(raw) - len(raw) % 4], dtype="<i4")
        return (wide >> 16).astype(np.int16)
    raise SpeechError(f"{label}: {8 * width}-bit samples; give 8, 16 or 32-bit PCM")


def wav_bytes(samples: Audio, rate: int = SAMPLE_RATE, channels: int = 1) -> bytes:
    """``samples`` (interleaved when ``channels`` > 1) as the bytes of a 16-bit WAV file."""
    buffer = io.BytesIO()
    with wave.open(buffer, "wb") as writer:
        writer.setnchannels(channels)
        writer.setsampwidth(2)
        writer.setframerate(rate)
        writer.writeframes(samples.astype("<i2").tobytes())
    return buffer.getvalue()


def write_wav(path: str | Path, samples: Audio, rate: int = SAMPLE_RATE) -> None:
    """Write ``samples`` as a mono 16-bit WAV; ``SpeechError`` when the path is unwritable."""
    try:
        Path(path).write_bytes(wav_bytes(samples, rate))
    except OSError as error:
        raise SpeechError(f"{path}: cannot be written ({error.strerror or error}); "
                          "check the folder exists") from None


def _power(signal: NDArray[np.float64]) -> float:
    return float(np.mean(signal ** 2)) if signal.size else 0.0


def add_noise(speech: Audio, noise: NDArray[np.float64], snr_db: float) -> Audio:
    """``speech`` plus ``noise`` scaled so that speech power / noise power is ``snr_db``.

    Speech power is measured where the speech is (samples above 1 % of the peak), so
    leading and trailing silence does not flatter the SNR.
    """
    clean = speech.astype(np.float64)
    loud = clean[np.abs(clean) > 0.01 * max(1.0, float(np.max(np.abs(clean))))]
    noise = np.resize(noise.astype(np.float64), clean.shape)
    scale = math.sqrt(_power(loud) / max(_power(noise), 1e-9) / 10 ** (snr_db / 10))
    return np.clip(np.round(clean + scale * noise), -32768, 32767).astype(np.int16)


def babble(voices: list[Audio], length: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """Babble noise: several talkers at once, each from a random offset, summed."""
    out = np.zeros(length)
    for talk in voices:
        if talk.size == 0:
            continue
        start = int(rng.integers(0, talk.size))
        out += np.resize(np.roll(talk.astype(np.float64), -start), length)
    return out


def tones(seconds: float, rng: np.random.Generator) -> Audio:
    """Music-like audio: a random melody of harmonic notes with a steady beat."""
    length = int(seconds * SAMPLE_RATE)
    out = np.zeros(length)
    position = 0
    while position < length:
        note = int(rng.integers(48, 84))
        duration = int(SAMPLE_RATE * float(rng.choice([0.125, 0.25, 0.5])))
        t = np.arange(min(duration, length - position)) / SAMPLE_RATE
        frequency = 440.0 * 2 ** ((note - 69) / 12)
        envelope = np.exp(-3.0 * t)
        wave_ = sum(np.sin(2 * np.pi * frequency * k * t) / k for k in (1, 2, 3))
        out[position:position + t.size] += envelope * wave_
        position += duration
    return np.clip(out / max(1e-9, float(np.max(np.abs(out)))) * 12000, -32768,
                   32767).astype(np.int16)


def denoise(samples: Audio, *, quiet_share: float = 0.2, over: float = 2.0,
            floor: float = 0.1) -> Audio:
    """Spectral subtraction for steady noise: the noise spectrum is the mean power of the
    quietest ``quiet_share`` of 32 ms frames; each bin keeps the gain
    ``max(floor, 1 - over * noise / power)``. Clean speech (quiet frames near silence)
    passes almost unchanged."""
    from scipy.signal import istft, stft

    if samples.size < 2048:
        return samples
    _, _, spectrum = stft(samples.astype(np.float64), fs=SAMPLE_RATE, nperseg=512,
                          noverlap=384)
    power = np.abs(spectrum) ** 2
    energy = power.sum(axis=0)
    quiet = energy <= np.quantile(energy, quiet_share)
    noise = power[:, quiet].mean(axis=1, keepdims=True)
    gain = np.maximum(floor, 1.0 - over * noise / np.maximum(power, 1e-12))
    _, cleaned = istft(spectrum * np.sqrt(gain), fs=SAMPLE_RATE, nperseg=512, noverlap=384)
    out: Audio = np.clip(np.round(cleaned[:samples.size]), -32768, 32767).astype(np.int16)
    return out
