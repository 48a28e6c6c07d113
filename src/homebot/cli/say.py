"""``homebot say "TEXT" -o FILE.wav``: the robot's voice (espeak-ng) into a WAV file."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from homebot.cli.voice import speak_to_file
from homebot.errors import SpeechError

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("say", help="speak a text with the robot's voice into a WAV")
    parser.add_argument("text", help="what to say, in quotes")
    parser.add_argument("-o", "--output", type=Path, required=True, metavar="FILE.wav",
                        help="WAV file to write (16 kHz mono 16-bit)")
    parser.add_argument("--voice", default="en-us",
                        help="espeak-ng voice: en-us (default), en, en-us+klatt, en+m3 ...")
    parser.add_argument("--rate", type=_rate, default=160, help="words a minute (80-450)")
    parser.set_defaults(handler=_say)


def _rate(text: str) -> int:
    if not text.strip().isdigit() or not 80 <= int(text) <= 450:
        raise SpeechError(f"--rate {text!r}: give words a minute from 80 to 450")
    return int(text)


def _say(args: argparse.Namespace) -> int:
    if not args.text.strip():
        raise SpeechError("there is nothing to say: give some text in quotes")
    speak_to_file([args.text], args.output, args.voice, args.rate)
    print(f"{args.output}: said {args.text!r}")
    return 0
