"""``homebot say``, ``listen`` and ``do --voice``: files in and out, bad files in one line."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

pytest.importorskip("pocketsphinx")
pytest.importorskip("espeakng_loader")

from homebot.cli import main
from homebot.speech.audio import read_wav, resample, wav_bytes, write_wav
from homebot.speech.voice import MAX_SPOKEN_CHARACTERS, espeak

if TYPE_CHECKING:
    from conftest import FailsCleanly

COMMAND = "Bring me a cola from the kitchen table"


@pytest.fixture(scope="module")
def command_wav(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("speech") / "command.wav"
    assert main(["say", COMMAND, "-o", str(path), "--voice", "en-us+klatt", "--rate",
                 "125"]) == 0
    return path


def test_say_writes_speech(command_wav: Path) -> None:
    audio = read_wav(command_wav)
    assert audio.size > 16_000 and np.abs(audio).max() > 1000


def test_listen_hears_the_steps(command_wav: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["listen", str(command_wav), "--json"]) == 0
    heard = json.loads(capsys.readouterr().out.splitlines()[0])
    assert heard["text"] == "bring me a cola from the kitchen table"
    assert [step["skill"] for step in heard["parse"]["steps"]] == [
        "navigate", "find_object", "pick", "navigate", "give"]


def test_listen_resamples_other_rates(command_wav: Path, tmp_path: Path,
                                      capsys: pytest.CaptureFixture[str]) -> None:
    other = tmp_path / "44k.wav"
    other.write_bytes(wav_bytes(resample(read_wav(command_wav), 16_000, 44_100), 44_100))
    assert main(["listen", str(other)]) == 0
    assert "heard: bring me a cola from the kitchen table" in capsys.readouterr().out


def test_do_voice_carries_the_command_out_and_speaks_the_reply(
        command_wav: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    reply = tmp_path / "reply.wav"
    assert main(["do", "--voice", str(command_wav), "--reply", str(reply), "--json"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert json.loads(lines[0])["heard"]["accepted"]
    assert json.loads(lines[-1])["success"]
    assert read_wav(reply).size > 16_000


def test_do_voice_with_noise_runs_no_skill(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    noise = tmp_path / "noise.wav"
    write_wav(noise, (np.random.default_rng(0).standard_normal(48_000) * 3000).astype(np.int16))
    assert main(["do", "--voice", str(noise), "--json"]) == 1
    report = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert report["steps"] == [] and not report["success"]


@pytest.mark.parametrize(("data", "expected"), [
    (b"", "the file is empty"),
    (b"bring me a cola\n", "not a WAV file"),
    (wav_bytes(np.zeros(600 * 8000, dtype=np.int16), 8000), "600 s long"),
])
@pytest.mark.parametrize("command", ["listen", "do"])
def test_bad_files_exit_2_in_one_line(tmp_path: Path, data: bytes, expected: str, command: str,
                                      fails_cleanly: FailsCleanly) -> None:
    path = tmp_path / "clip.wav"
    path.write_bytes(data)
    argv = ["listen", str(path)] if command == "listen" else ["do", "--voice", str(path)]
    fails_cleanly(main(argv), expected)


def test_do_wants_text_or_voice_not_both(command_wav: Path,
                                         fails_cleanly: FailsCleanly) -> None:
    fails_cleanly(main(["do", COMMAND, "--voice", str(command_wav)]), "not both")
    fails_cleanly(main(["do"]), "give the command in quotes")


def test_say_refuses_nothing_and_bad_rates(tmp_path: Path,
                                           fails_cleanly: FailsCleanly) -> None:
    fails_cleanly(main(["say", " ", "-o", str(tmp_path / "a.wav")]), "nothing to say")
    fails_cleanly(main(["say", "hi", "-o", str(tmp_path / "a.wav"), "--rate", "9"]),
                  "--rate '9'")
    fails_cleanly(main(["say", "hi", "-o", str(tmp_path / "no" / "a.wav")]),
                  "cannot be written")
    fails_cleanly(main(["say", "hi", "-o", str(tmp_path / "b.wav"), "--voice",
                  "nosuchvoice"]), "no voice 'nosuchvoice'")


def test_say_refuses_a_text_too_long_to_speak_at_once(tmp_path: Path,
                                                      fails_cleanly: FailsCleanly) -> None:
    # 96 KB of text took 2.25 GB to synthesise; it is refused before espeak-ng starts on it
    path = tmp_path / "long.wav"
    fails_cleanly(main(["say", "bring me a cola " * 6_000, "-o", str(path)]),
                  "a text of 96,000 characters is too long to say at once")
    assert not path.exists()
    longest = "a" * MAX_SPOKEN_CHARACTERS
    assert espeak().synthesise(longest).size > 0

