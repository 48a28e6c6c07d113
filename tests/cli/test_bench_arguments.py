"""Bad benchmark (and plan/golog) arguments: exit 2 with one line, never a traceback or a hang."""

from __future__ import annotations

from pathlib import Path

import pytest

from homebot.cli import main

BAD = [
    (["bench", "parse", "--count", "0"], "--count '0'"),
    (["bench", "parse", "--count", "-5"], "--count '-5'"),
    (["bench", "parse", "--count", "10000000000"], "--count '10000000000'"),
    (["bench", "parse", "--repeat", "0"], "--repeat '0'"),
    (["bench", "parse", "--seed", "-1"], "--seed '-1'"),
    (["bench", "parse", "--seed", "1.5"], "--seed '1.5'"),
    (["bench", "parse", "--commands", "/no/such/commands.tsv"], "cannot be read"),
    (["bench", "fetch", "--tasks", "0"], "--tasks '0'"),
    (["bench", "fetch", "--seed", "99999999999"], "--seed"),
    (["bench", "robustness", "--tasks", "-1"], "--tasks '-1'"),
    (["bench", "gpsr", "--commands", "0"], "--commands '0'"),
    (["bench", "navigation", "--repeat", "0"], "--repeat '0'"),
    (["bench", "navigation", "--goals", "-1"], "--goals '-1'"),
    (["bench", "navigation", "--walkers", "99"], "--walkers '99'"),
    (["bench", "golog", "--repeats", "0"], "--repeats '0'"),
    (["bench", "golog", "--maze-horizon", "40"], "--maze-horizon '40'"),
    (["bench", "htn", "--sizes", "25", "0"], "--sizes '0'"),
    (["bench", "inference", "--worlds", "0"], "--worlds '0'"),
    (["bench", "kb", "--individuals", "-1"], "--individuals '-1'"),
    (["plan", "bring_object", "pringles", "Alex", "--max-depth", "-1"], "--max-depth -1"),
    (["plan", "bring_object", "pringles", "Alex", "--max-expansions", "0"], "--max-expansions"),
]


@pytest.mark.parametrize(("argv", "named"), BAD, ids=[" ".join(argv[:4]) for argv, _ in BAD])
def test_a_bad_argument_is_exit_2_with_one_line(argv: list[str], named: str,
                                                capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("error: ") and named in lines[0]
    assert "Traceback" not in captured.err and captured.out == ""


def test_an_unreadable_commands_file_is_an_error_not_replaced(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    commands = tmp_path / "commands.tsv"
    commands.write_bytes(b"")
    commands.chmod(0)
    try:
        readable = commands.open("rb")  # root reads anything: then the test cannot apply
        readable.close()
        pytest.skip("this account reads unreadable files")
    except PermissionError:
        pass
    assert main(["bench", "parse", "--commands", str(commands)]) == 2
    assert "cannot be read" in capsys.readouterr().err


def test_an_empty_commands_file_is_an_error(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    commands = tmp_path / "commands.tsv"
    commands.write_text("", encoding="utf-8")
    robocup = Path(__file__).resolve().parents[1] / "world" / "data" / "robocup_placeholders"
    assert main(["bench", "parse", "--commands", str(commands), "--robocup",
                 str(robocup)]) == 2
    assert "no commands" in capsys.readouterr().err


@pytest.mark.parametrize("text", ["", "  \n// nothing here\n"])
def test_golog_check_on_an_empty_file_says_it_is_empty(
        tmp_path: Path, text: str, capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "empty.golog"
    program.write_text(text, encoding="utf-8")
    assert main(["golog", "check", str(program)]) == 2
    assert "empty" in capsys.readouterr().err
