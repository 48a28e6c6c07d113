"""``homebot listen [FILE.wav|-]``: hear spoken commands (or answers) and show what they mean.

From a WAV file, from stdin (``-``, or whenever stdin is not a terminal), or from the
microphone when none is given and ``sounddevice`` finds one. The audio is cut into
utterances by voice activity detection; each is decoded with the world's grammar and
trigram model, reconciled, and a command is parsed into skill steps.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from homebot.cli.options import load_world
from homebot.cli.voice import read_audio
from homebot.errors import SpeechError

__all__ = ["register"]

_MAX_RECORD = 60


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("listen", help="hear spoken commands and show their steps")
    parser.add_argument("audio", nargs="?", type=Path, metavar="FILE.wav",
                        help="WAV file to hear ('-' for stdin; default: the microphone, "
                             "or stdin when it is not a terminal)")
    parser.add_argument("--world", default="apartment",
                        help="world file, or a shipped world name (default: apartment)")
    parser.add_argument("--expect", choices=("command", "yes_no", "drink"), default="command",
                        help="the dialogue's state: what the robot listens for (default: a "
                             "command)")
    parser.add_argument("--seconds", type=_seconds, default=8,
                        help=f"microphone: how long to record (1-{_MAX_RECORD}, default 8)")
    parser.add_argument("--json", action="store_true", help="one JSON object per utterance")
    parser.set_defaults(handler=_listen)


def _seconds(text: str) -> int:
    if not text.strip().isdigit() or not 1 <= int(text) <= _MAX_RECORD:
        raise SpeechError(f"--seconds {text!r}: give a whole number from 1 to {_MAX_RECORD}")
    return int(text)


def _record(seconds: int) -> Any:
    """Audio from the default microphone (sounddevice), or ``SpeechError`` saying what to do."""
    try:
        import sounddevice
    except (ImportError, OSError):
        raise SpeechError("no microphone support (pip install sounddevice); give a WAV file: "
                          "homebot listen FILE.wav") from None
    from homebot.speech.audio import SAMPLE_RATE

    try:
        print(f"listening for {seconds} s ...", file=sys.stderr)
        audio = sounddevice.rec(seconds * SAMPLE_RATE, samplerate=SAMPLE_RATE, channels=1,
                                dtype="int16")
        sounddevice.wait()
    except Exception as error:  # PortAudioError and friends: no device, busy device
        raise SpeechError(f"the microphone cannot be read ({error}); give a WAV file: "
                          "homebot listen FILE.wav") from None
    return audio[:, 0]


def _listen(args: argparse.Namespace) -> int:
    from homebot.language import Vocabulary, parse_command
    from homebot.speech.recognizer import Recognizer

    if args.audio is not None:
        audio = read_audio(args.audio)
    elif not sys.stdin.isatty():
        audio = read_audio(Path("-"))
    else:
        audio = _record(args.seconds)
    world = load_world(args)
    recognizer = Recognizer.for_world(world)
    if args.expect not in recognizer.grammars:
        raise SpeechError(f"world '{world.name}' has no drinks to listen for; "
                          "use --expect command or yes_no")
    utterances = recognizer.segmenter.utterances(audio)
    if not utterances:
        _show(args, {"text": None, "accepted": False, "reason": "no_speech"})
        return 1
    vocabulary = Vocabulary.from_world(world)
    heard_any = False
    for utterance in utterances:
        hearing = recognizer.decode(utterance.of(audio), args.expect)
        shown = {"start": round(utterance.start / 16_000, 2), **hearing.to_dict()}
        if hearing.text is not None and args.expect == "command":
            shown["parse"] = parse_command(hearing.text, vocabulary).to_dict()
        heard_any = heard_any or bool(hearing)
        _show(args, shown)
    return 0 if heard_any else 1


def _show(args: argparse.Namespace, shown: dict[str, Any]) -> None:
    if args.json:
        print(json.dumps(shown, ensure_ascii=False))
        return
    where = f"[{shown['start']:.2f} s] " if "start" in shown else ""
    if not shown["accepted"]:
        print(f"{where}rejected ({shown['reason']})")
        return
    print(f"{where}heard: {shown['text']} ({shown['reason']})")
    parse = shown.get("parse")
    if parse is not None:
        for number, step in enumerate(parse.get("steps") or [], 1):
            args_ = ", ".join(f"{key}={value}" for key, value in step.items() if key != "skill")
            print(f"  {number}. {step['skill']}({args_})")
        if parse.get("question") or parse.get("reason"):
            print(f"  {parse.get('question') or parse.get('reason')}")
