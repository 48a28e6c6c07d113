"""``homebot parse "COMMAND"``: what a GPSR command means as skill steps (or a question)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from homebot.app.world_names import world_vocabulary
from homebot.errors import LanguageError
from homebot.files import read_text_file
from homebot.language import ParseResult, Vocabulary, parse_command

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("parse", help="turn a command into skill steps")
    parser.add_argument("command", nargs="?", help="the command, in quotes")
    parser.add_argument("--world", default="apartment",
                        help="world file, or a shipped world name (default: apartment)")
    parser.add_argument("--json", action="store_true", help="print the result as JSON")
    parser.add_argument("--file", type=Path,
                        help="parse every line of FILE; one JSON object a line")
    parser.set_defaults(handler=_parse)


def _parse(args: argparse.Namespace) -> int:
    if (args.command is None) == (args.file is None):
        raise LanguageError('give one command in quotes, or --file FILE (not both)')
    vocabulary = world_vocabulary(args.world)
    if args.file is not None:
        return _parse_file(args.file, vocabulary)
    result = parse_command(args.command, vocabulary)
    print(json.dumps(result.to_dict(), ensure_ascii=False) if args.json else _readable(result))
    return 0 if result else 1


def _parse_file(path: Path, vocabulary: Vocabulary) -> int:
    lines = read_text_file(path, LanguageError, "text", "file of commands, one a line"
                           ).splitlines()
    status = 0
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            result = parse_command(line, vocabulary)
        except LanguageError as error:
            raise LanguageError(f"{path}: line {number}: {error}") from None
        print(json.dumps({"command": line, **result.to_dict()}, ensure_ascii=False))
        status = status or (0 if result else 1)
    return status


def _readable(result: ParseResult) -> str:
    if result.question is not None:
        return f"clarify: {result.question}"
    if result.reason is not None:
        return f"reject: {result.reason}"
    return "\n".join(f"{number}. {step}" for number, step in enumerate(result.steps, 1))
