"""What ``do --voice``, ``listen`` and ``say`` share: hearing a WAV, speaking into one."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from homebot.errors import SpeechError
from homebot.files import SIZE_LIMITS, size_text

__all__ = ["NOT_UNDERSTOOD", "add_voice_options", "hear_file", "read_audio", "speak_to_file",
           "spoken_or_typed"]

# What the robot says when it heard nothing it could take as a command.
NOT_UNDERSTOOD = "Sorry, I did not catch that. Please say the command again."


def add_voice_options(parser: argparse.ArgumentParser) -> None:
    """``--voice FILE.wav`` (hear the command) and ``--reply FILE.wav`` (speak the answer)."""
    parser.add_argument("--voice", type=Path, metavar="FILE.wav",
                        help="hear the command from a WAV file ('-' reads stdin) instead of "
                             "text; needs the speech extra")
    parser.add_argument("--reply", type=Path, metavar="FILE.wav",
                        help="write what the robot says as speech (espeak-ng) to this WAV")


def read_audio(source: Path) -> Any:
    """The audio of a WAV file, or of stdin for ``-`` (16 kHz mono int16)."""
    from homebot.speech.audio import read_wav

    if str(source) == "-":
        if sys.stdin.isatty():
            raise SpeechError("stdin is a terminal; pipe a WAV file in: "
                              "homebot listen - < command.wav")
        limit = SIZE_LIMITS["audio"]
        data = sys.stdin.buffer.read(limit + 1)
        if len(data) > limit:
            raise SpeechError(f"<stdin>: more than {size_text(limit)}, the limit for a WAV "
                              "file; pipe in one command's recording")
        return read_wav(data, name="<stdin>")
    return read_wav(source)


def hear_file(source: Path, world: Any, state: str = "command") -> Any:
    """A ``Hearing`` of the command in a WAV file, with the world's grammars."""
    from homebot.speech.recognizer import Recognizer

    audio = read_audio(source)
    return Recognizer.for_world(world).hear(audio, state)


def speak_to_file(texts: Sequence[str], path: Path | None, voice: str = "en-us",
                  rate: int = 160) -> None:
    """Say ``texts`` one after the other (half a second apart) into the WAV at ``path``."""
    if path is None or not texts:
        return
    import numpy as np

    from homebot.speech.audio import SAMPLE_RATE, write_wav
    from homebot.speech.voice import VoiceSettings, espeak

    settings = VoiceSettings(voice, rate)
    pause = np.zeros(SAMPLE_RATE // 2, dtype=np.int16)
    parts = []
    for text in texts:
        if text.strip():
            parts += [espeak().synthesise(text, settings), pause]
    write_wav(path, np.concatenate(parts) if parts else pause)


def spoken_or_typed(args: argparse.Namespace, world: Any) -> str | None:
    """The command of ``do``: typed, or heard from ``--voice``; None (after the robot said
    so) when the recording held no command it could take."""
    if (args.command is None) == (args.voice is None):
        raise SpeechError('give the command in quotes, or --voice FILE.wav (not both)')
    if args.voice is None:
        return str(args.command)
    hearing = hear_file(args.voice, world)
    if args.json:
        print(json.dumps({"heard": hearing.to_dict()}, ensure_ascii=False))
    else:
        from rich.console import Console
        from rich.markup import escape

        heard = escape(hearing.text) if hearing else f"nothing I can do ({hearing.reason})"
        Console().print(f"  [cyan]heard:[/] {heard}", highlight=False)
    if hearing:
        return str(hearing.text)
    if args.json:
        print(json.dumps({"success": False, "steps": [], "speech": [NOT_UNDERSTOOD],
                          "sim_time": 0.0}, ensure_ascii=False))
    else:
        print(f"  robot: {NOT_UNDERSTOOD}")
    speak_to_file([NOT_UNDERSTOOD], args.reply)
    return None
