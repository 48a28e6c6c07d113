"""The README keeps its promises: at most 400 lines, every package in its layer table, and every
``homebot ...`` command in it parses with the real command line; the quick ones run.

Commands are taken from the README's ``sh`` code blocks (one command a line; a ``#`` starts a
comment; a pipe or redirection ends the command) and from the figures table's command column.
A ``yaml`` block whose first line is ``# NAME.yaml`` is written to NAME.yaml before the commands
run, so the README's task file is the one its commands read. The commands run in the README's
order in one scratch folder, as a reader would type them, so a file one writes the next reads.
"""

from __future__ import annotations

import io
import re
import shlex
from collections.abc import Iterator
from pathlib import Path

import pytest

from homebot.cli import command_line_argument_parser, main

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
MAX_LINES = 400

SHELL_OPERATORS = {"|", "||", "&&", ";", ">", ">>", "<", "2>", "&"}
# Commands that run in a few seconds in the symbolic fidelity with the core install: the test
# runs them and wants exit status 0. Matched on the leading words of the argument list.
QUICK = [
    ("--version",), ("parse",), ("world", "show"), ("world", "check"), ("world", "map"),
    ("world", "map-check"), ("world", "from-pyrobosim"), ("kb",), ("plan",),
    ("golog", "check"), ("golog", "plan"), ("golog", "maintain"), ("sitlog", "show"),
    ("do",), ("run-task",), ("scenario", "fetch"), ("scenario", "jenny"),
    ("scenario", "supermarket"), ("scenario", "butler"), ("scenario", "order_cups"),
    ("chat",),
]
# What a reader types into the commands that read it: `chat` ends at "quit".
TYPED = {"chat": "quit\n"}
# Never run here: they need another extra, run long, serve until stopped or read a terminal.
SLOW_OPTIONS = {"--fidelity", "--robot"}


def fenced_blocks(text: str) -> Iterator[tuple[str, str]]:
    """Each fenced code block of a Markdown text: (language, body)."""
    for match in re.finditer(r"^```(\w*)\n(.*?)^```", text, flags=re.MULTILINE | re.DOTALL):
        yield match.group(1), match.group(2)


def command_of(line: str) -> list[str] | None:
    """The ``homebot`` arguments a shell line runs (without ``homebot``), or None."""
    words = shlex.split(line, comments=True)
    if "homebot" not in words:
        return None
    arguments = words[words.index("homebot") + 1:]
    for position, word in enumerate(arguments):
        if word in SHELL_OPERATORS:
            return arguments[:position]
    return arguments


def block_commands(text: str) -> list[list[str]]:
    """Every ``homebot`` command of the ``sh`` blocks, in order."""
    commands = []
    for language, body in fenced_blocks(text):
        if language != "sh":
            continue
        for line in body.splitlines():
            command = command_of(line)
            if command is not None:
                commands.append(command)
    return commands


def table_commands(text: str) -> list[list[str]]:
    """The figures table's commands: inline code ``homebot ...`` in table rows."""
    commands = []
    for line in text.splitlines():
        if line.startswith("|"):
            for span in re.findall(r"`(homebot [^`]+)`", line):
                command = command_of(span)
                assert command is not None
                commands.append(command)
    return commands


def files_to_write(text: str) -> dict[str, str]:
    """The README's files: ``yaml`` blocks whose first line is ``# NAME.yaml``."""
    files = {}
    for language, body in fenced_blocks(text):
        first = body.splitlines()[0] if body else ""
        named = re.fullmatch(r"# ([\w.-]+\.ya?ml)", first.strip())
        if language == "yaml" and named:
            files[named.group(1)] = body
    return files


def needs_speech(command: list[str]) -> bool:
    """Hearing or speaking: needs the speech extra."""
    return command[0] in {"say", "listen"} or "--voice" in command


def is_quick(command: list[str]) -> bool:
    return (any(tuple(command[:len(prefix)]) == prefix for prefix in QUICK)
            and not needs_speech(command) and not SLOW_OPTIONS & set(command))


README_TEXT = README.read_text(encoding="utf-8")
ALL_COMMANDS = block_commands(README_TEXT) + table_commands(README_TEXT)


def test_the_readme_is_at_most_400_lines() -> None:
    lines = len(README_TEXT.splitlines())
    assert lines <= MAX_LINES, f"README.md has {lines} lines; move detail to docs/"


def test_the_readme_shows_commands_of_every_kind() -> None:
    groups = {command[0] for command in ALL_COMMANDS}
    assert {"do", "parse", "chat", "serve", "scenario", "world", "kb", "listen", "ros", "sim",
            "bench"} <= groups
    assert any(is_quick(command) for command in ALL_COMMANDS)


def test_the_layer_table_names_every_package() -> None:
    packages = sorted(path.name for path in (ROOT / "src" / "homebot").iterdir()
                      if (path / "__init__.py").exists() and path.name != "data")
    missing = [name for name in packages if f"`homebot.{name}`" not in README_TEXT]
    assert not missing, f"README.md's layer table leaves out {missing}"
    named = set(re.findall(r"`homebot\.(\w+)`", README_TEXT))
    modules = {path.stem for path in (ROOT / "src" / "homebot").glob("*.py")}
    absent = sorted(named - set(packages) - modules)
    assert not absent, f"README.md names packages that do not exist: {absent}"


@pytest.mark.parametrize("command", ALL_COMMANDS, ids=shlex.join)
def test_every_command_parses(command: list[str]) -> None:
    parser = command_line_argument_parser()
    try:
        parser.parse_args(command)
    except SystemExit as stop:  # argparse's way out: 0 for --help and --version
        assert stop.code == 0, f"`homebot {shlex.join(command)}` does not parse"


@pytest.fixture
def reader_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A scratch folder that looks like the repository's root to the README's commands."""
    for name in ("src", "tests"):
        (tmp_path / name).symlink_to(ROOT / name)
    for name, body in files_to_write(README_TEXT).items():
        (tmp_path / name).write_text(body, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run_in_order(commands: list[list[str]], capsys: pytest.CaptureFixture[str],
                 monkeypatch: pytest.MonkeyPatch) -> None:
    failures = []
    for command in commands:
        monkeypatch.setattr("sys.stdin", io.StringIO(TYPED.get(command[0], "")))
        try:
            status = main(command)
        except SystemExit as stop:
            status = stop.code if isinstance(stop.code, int) else 1
        output = capsys.readouterr()
        if status != 0:
            failures.append(f"homebot {shlex.join(command)}: exit {status}\n{output.err[-400:]}")
    assert not failures, "\n".join(failures)


def test_the_quick_commands_run(reader_folder: Path, capsys: pytest.CaptureFixture[str],
                                monkeypatch: pytest.MonkeyPatch) -> None:
    run_in_order([command for command in block_commands(README_TEXT) if is_quick(command)],
                 capsys, monkeypatch)


def test_the_speech_commands_run(reader_folder: Path, capsys: pytest.CaptureFixture[str],
                                 monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("pocketsphinx", reason="needs the speech extra")
    pytest.importorskip("espeakng_loader", reason="needs the speech extra")
    speech = [command for command in block_commands(README_TEXT)
              if needs_speech(command) and not SLOW_OPTIONS & set(command)]
    assert speech
    run_in_order(speech, capsys, monkeypatch)
