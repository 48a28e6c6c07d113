"""``homebot kb``: check, query (text and JSON) and explain, run in-process."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main


def _run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_check_reports_counts(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = _run(capsys, "kb", "check", "butler")
    assert status == 0
    assert "8 classes, 11 individuals" in out and "0 warnings" in out


def test_check_reports_a_syntax_error_with_line_and_column(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    bad = tmp_path / "bad.kb"
    bad.write_text("[class(top,none,[],[],[]),\n class(a,top,[[x=>y=>z,0]],[],[])]")
    status, out, err = _run(capsys, "kb", "check", str(bad))
    assert status == 2
    assert "line 2, column" in err and "Traceback" not in err
    assert out == ""


def test_check_lists_warnings_with_positions(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    kb = tmp_path / "kb.kb"
    kb.write_text("[class(top,none,[[fly,0],[not(fly),0]],[],[])]")
    status, out, _ = _run(capsys, "kb", "check", str(kb))
    assert status == 0
    assert "1 warnings" in out and "line 1, column 26" in out


def test_query_value_and_values(capsys: pytest.CaptureFixture[str]) -> None:
    assert _run(capsys, "kb", "query", "animals", "value", "pete", "live")[1] == "mexico\n"
    status, out, _ = _run(capsys, "kb", "query", "butler", "values", "noodles", "loc", "--json")
    assert status == 0
    assert json.loads(out) == ["shelf_food", "shelf_snacks", "shelf_drinks"]


@pytest.mark.parametrize(
    ("service", "argument", "expected"),
    [
        ("class_extension", "birds", ["pete", "arthur"]),
        ("property_extension", "fly", [["pete", "yes"], ["arthur", "no"]]),
        ("relation_extension", "eat", [["pete", ["pete", "arthur"]]]),
        ("explanation_extension", "live", [["pete", [{"live": "mexico"}, {"work": "mexico"}]]]),
        ("classes_of_individual", "arthur", ["penguins", "birds", "animals", "top"]),
        (
            "properties_of_individual",
            "pete",
            [{"size": "large"}, "fly", {"not": "swim"}, {"live": "mexico"}],
        ),
        (
            "relations_of_individual",
            "pete",
            [{"work": "mexico"}, {"born": "argentina"}, {"like": "mexico"},
             {"eat": ["pete", "arthur"]}],
        ),
        ("explanation_of_individual", "pete", [[{"live": "mexico"}, {"work": "mexico"}]]),
    ],
)
def test_the_eight_services_as_json(
    capsys: pytest.CaptureFixture[str], service: str, argument: str, expected: object
) -> None:
    status, out, _ = _run(capsys, "kb", "query", "animals", service, argument, "--json")
    assert status == 0
    assert json.loads(out) == expected


def test_query_prints_kb_syntax_without_json(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = _run(capsys, "kb", "query", "animals", "properties-of-individual", "arthur")
    assert status == 0
    assert out == "[swim, not(fly)]\n"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("kb", "query", "animals", "colour_of", "pete"), "unknown service"),
        (("kb", "query", "animals", "value", "pete"), "takes ENTITY PROPERTY"),
        (("kb", "query", "animals", "value", "petr", "fly"), "did you mean 'pete'"),
        (("kb", "query", "animals", "value", "pete", "a=>"), "line 1, column 4"),
        (("kb", "query", "nowhere.kb", "value", "pete", "fly"), "no KB file"),
        (("kb", "explain", "animals", "nobody"), "unknown"),
        (("kb",), "name a kb command"),
    ],
)
def test_mistakes_exit_2_with_a_message(
    capsys: pytest.CaptureFixture[str], argv: tuple[str, ...], message: str
) -> None:
    status, _, err = _run(capsys, *argv)
    assert status == 2
    assert message in " ".join(err.split())
    assert "Traceback" not in err


def test_explain_says_why(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    kb = tmp_path / "butler.kb"
    text = (Path(__file__).resolve().parents[2] / "src/homebot/data/kb/butler.kb").read_text()
    kb.write_text(text.replace("[id=>coke, [], []]", "[id=>coke, [[misplaced,0]], []]"))
    status, out, _ = _run(capsys, "kb", "explain", str(kb), "coke")
    assert status == 0
    assert "coke: misplaced because moved_by=>child (weight 1, from object)" in out
