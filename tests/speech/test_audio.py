"""WAV files in and out: resampling, channels, noise at an SNR, and the files refused."""

from __future__ import annotations

import wave
from pathlib import Path

import numpy as np
import pytest

from homebot.errors import SpeechError
from homebot.speech.audio import (
    SAMPLE_RATE,
    add_noise,
    denoise,
    read_wav,
    resample,
    tones,
    wav_bytes,
    write_wav,
)


def _tone(seconds: float, rate: int, frequency: float = 440.0) -> np.ndarray:
    t = np.arange(int(seconds * rate)) / rate
    return (np.sin(2 * np.pi * frequency * t) * 10000).astype(np.int16)


def test_a_16_khz_file_reads_back_as_written(tmp_path: Path) -> None:
    samples = _tone(0.5, SAMPLE_RATE)
    write_wav(tmp_path / "a.wav", samples)
    assert np.array_equal(read_wav(tmp_path / "a.wav"), samples)


def test_other_rates_and_stereo_are_resampled_to_16_khz_mono() -> None:
    stereo = np.repeat(_tone(1.0, 44_100)[:, None], 2, axis=1).reshape(-1)
    heard = read_wav(wav_bytes(stereo, 44_100, channels=2))
    assert heard.size == SAMPLE_RATE
    spectrum = np.abs(np.fft.rfft(heard.astype(float)))
    assert abs(np.argmax(spectrum) * SAMPLE_RATE / heard.size - 440.0) < 2.0
    assert resample(_tone(1.0, 8000), 8000).size == SAMPLE_RATE


def test_eight_bit_samples_are_widened() -> None:
    buffer = wav_bytes(np.zeros(10, dtype=np.int16))  # a header to copy
    import io

    out = io.BytesIO()
    with wave.open(out, "wb") as writer:
        writer.setnchannels(1)
        writer.setsampwidth(1)
        writer.setframerate(SAMPLE_RATE)
        writer.writeframes(bytes([128, 255, 0]))
    assert buffer and list(read_wav(out.getvalue())) == [0, 127 * 256, -128 * 256]


@pytest.mark.parametrize(("data", "expected"), [
    (b"", "the file is empty"),
    (b"bring me a cola from the kitchen\n", "not a WAV file"),
    (b"RIFF\x00\x00\x00\x00WAVEfmt junk", "not a PCM WAV file"),
    (wav_bytes(np.zeros(0, dtype=np.int16)), "holds no samples"),
    (wav_bytes(np.zeros(16000, dtype=np.int16))[:50],
     "the WAV ends after 6 of the 32000 bytes of samples its header declares"),
])
def test_unusable_files_are_refused_with_a_reason(tmp_path: Path, data: bytes,
                                                  expected: str) -> None:
    path = tmp_path / "clip.wav"
    path.write_bytes(data)
    with pytest.raises(SpeechError, match=expected):
        read_wav(path)


def test_a_ten_minute_file_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "long.wav"
    write_wav(path, np.zeros(600 * 8000, dtype=np.int16), rate=8000)
    with pytest.raises(SpeechError, match="600 s long"):
        read_wav(path)


def test_missing_files_and_folders_are_named(tmp_path: Path) -> None:
    with pytest.raises(SpeechError, match="cannot read"):
        read_wav(tmp_path / "nothing.wav")
    with pytest.raises(SpeechError, match="cannot read it \\(it is a folder\\)"):
        read_wav(tmp_path)


def test_noise_is_added_at_the_asked_snr() -> None:
    rng = np.random.default_rng(0)
    speech = _tone(1.0, SAMPLE_RATE)
    noise = rng.standard_normal(speech.size)
    noisy = add_noise(speech, noise, 10.0)
    added = noisy.astype(float) - speech
    snr = 10 * np.log10(np.mean(speech.astype(float) ** 2) / np.mean(added ** 2))
    assert abs(snr - 10.0) < 0.3


def test_denoising_lowers_steady_noise_and_keeps_the_tone() -> None:
    rng = np.random.default_rng(1)
    clip = np.concatenate([np.zeros(8000, dtype=np.int16), _tone(1.0, SAMPLE_RATE),
                           np.zeros(8000, dtype=np.int16)])
    noisy = add_noise(clip, rng.standard_normal(clip.size), 5.0)
    cleaned = denoise(noisy)
    before = np.mean((noisy.astype(float) - clip) ** 2)
    after = np.mean((cleaned.astype(float) - clip) ** 2)
    assert after < 0.5 * before


def test_tones_are_deterministic_by_seed() -> None:
    one = tones(1.0, np.random.default_rng(3))
    assert np.array_equal(one, tones(1.0, np.random.default_rng(3)))
    assert one.size == SAMPLE_RATE and np.abs(one).max() > 1000
