"""``homebot golog check|plan|run`` in-process: exit codes and output."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main

DATA = Path(__file__).resolve().parents[2] / "src" / "homebot" / "data" / "golog"


def test_check_a_shipped_file_against_its_domain(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "check", str(DATA / "order_cups.golog"), "--domain", "cups"]) == 0
    assert "2 procedure(s) (order_cups_demo, sort_cups)" in capsys.readouterr().out


def test_check_points_at_the_line_of_a_syntax_error(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.golog"
    bad.write_text("proc p\n  a;\n  while x do b\nendproc\n")
    assert main(["golog", "check", str(bad)]) == 2
    err = "".join(capsys.readouterr().err.split())
    assert "bad.golog:4:1:expected'endwhile'" in err


def test_check_names_an_unknown_action(tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "typo.golog"
    bad.write_text("proc p\n  stak(a, b)\nendproc\n")
    assert main(["golog", "check", str(bad), "--domain", "blocks"]) == 2
    err = "".join(capsys.readouterr().err.split())
    assert "didyoumean'stack'?" in err and f"{bad}:2:3:procedurep:" in err


def test_a_missing_file_is_an_error_not_a_crash(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "check", "/nonexistent/x.golog"]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_a_file_that_is_not_utf8_is_an_error_not_a_crash(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    binary = tmp_path / "binary.golog"
    binary.write_bytes(b"proc p\n  \xff\xfe\nendproc\n")
    assert main(["golog", "check", str(binary)]) == 2
    assert "not UTF-8" in capsys.readouterr().err


def test_plan_prints_the_policy_with_markers(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "plan", "build_tower(4)", "--domain", "blocks", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["value"] == 7.0 and result["probability"] == 1.0
    assert "M(poss(stack(c, table)), true)" in result["policy"]


def test_plan_needs_a_solve(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "plan", "park", "--domain", "elevator"]) == 2
    assert "does not begin with solve" in capsys.readouterr().err


def test_run_with_an_added_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    extra = tmp_path / "extra.golog"
    extra.write_text("proc twice\n  up; up\nendproc\n")
    assert main(["golog", "run", "twice; open", "--domain", "elevator", "--file", str(extra),
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actions"] == ["up", "up", "open"]


def test_run_reports_a_blocked_program_with_exit_1(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "run", "waitFor(alarm)", "--domain", "elevator"]) == 1
    assert "blocked" in capsys.readouterr().out


def test_a_search_with_no_end_gives_up_instead_of_hanging(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "run", "search(star(up | down); ?(false))", "--domain",
                 "elevator"]) == 1
    assert "blocked" in capsys.readouterr().out


@pytest.mark.parametrize(("argv", "words"), [
    (["golog", "run", "pickBest(f, {1, 2}, up)", "--domain", "elevator"], "not a number"),
    (["golog", "plan", "solve(x, reward, build_tower(3))", "--domain", "blocks"],
     "must be a whole number"),
    (["golog", "run", "up(", "--domain", "elevator"], "<command line>:1:4"),
    (["golog", "plan", "solve(3, 1, while true do nil endwhile)", "--domain", "elevator"],
     "goes round without acting"),
])
def test_mistakes_on_the_command_line_exit_2(argv: list[str], words: str,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    assert words in " ".join(capsys.readouterr().err.split())


@pytest.mark.parametrize(("program", "words"), [
    ("prob(abc, up, down)", "write a number from 0 to 1"),
    ('?(floor + "a" = 2)', "numbers with numbers"),
    ("?(1 / 0 = 2)", "divides by zero"),
    ("pi(x, 3, up)", "not a finite set"),
    ("?(floor + true = 4)", "numbers with numbers"),
    ("?(true < 2)", "numbers with numbers"),
    ("(" * 3000 + "up" + ")" * 3000, "nested too deeply"),
])
def test_programs_that_cannot_be_evaluated_exit_2(program: str, words: str,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "run", program, "--domain", "elevator"]) == 2
    assert words in " ".join(capsys.readouterr().err.split())


def test_true_is_not_the_number_one(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["golog", "run", "if true = 1 then up else down endif", "--domain",
                 "elevator"]) == 0
    assert capsys.readouterr().out.split()[:2] == ["action:", "down"]
