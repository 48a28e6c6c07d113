"""The command line imports a group's module only when it is chosen."""

from __future__ import annotations

import argparse
import ast
import subprocess
import sys

import pytest

from homebot.cli import COMMAND_GROUPS, command_line_argument_parser, main
from homebot.cli.modules import LazySubcommands


def _groups(parser: argparse.ArgumentParser) -> LazySubcommands:
    action = next(a for a in parser._actions if isinstance(a, LazySubcommands))
    return action


def test_help_lines_of_the_table_agree_with_the_modules() -> None:
    subparsers = _groups(command_line_argument_parser())
    before = {choice.dest: choice.help for choice in subparsers._choices_actions}
    subparsers.load_all()
    after = {choice.dest: choice.help for choice in subparsers._choices_actions}
    assert list(after) == list(COMMAND_GROUPS)
    assert before == after == {name: text for name, (_, text) in COMMAND_GROUPS.items()}


def test_help_imports_no_command_module() -> None:
    code = ("import sys\nfrom homebot.cli import main\n"
            "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m.startswith('homebot.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.splitlines()[-1]
    loaded = ast.literal_eval(out)
    assert loaded == ["homebot.cli", "homebot.cli.modules", "homebot.errors"]


def test_a_chosen_benchmark_imports_only_itself() -> None:
    code = ("import sys\nfrom homebot.cli import main\n"
            "try:\n    main(['bench', 'kb', '--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m.startswith('homebot.bench.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.splitlines()[-1]
    # kb and the argument types every benchmark shares (bench/arguments.py), no other benchmark
    assert ast.literal_eval(out) == ["homebot.bench.arguments", "homebot.bench.kb"]


def test_an_unknown_command_is_still_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["nosuch"])
    assert exit_info.value.code == 2
    assert "invalid choice: 'nosuch'" in capsys.readouterr().err
