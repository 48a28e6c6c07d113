"""``homebot chat`` and ``homebot do --answer``, in-process."""

from __future__ import annotations

import io
import json

import pytest

from homebot.cli import main


def test_chat_keeps_one_home_across_commands(monkeypatch: pytest.MonkeyPatch,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    lines = ["pick up the kiwi from the dining table", "put it on the desk",
             "ask Lisa what she would like to drink", "go to the table", "cancel", "quit"]
    monkeypatch.setattr("sys.stdin", io.StringIO("\n".join(lines) + "\n"))
    assert main(["chat", "--world", "family_home", "--seed", "2"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "Lisa would like a beer." in out
    assert "Which table do you mean" in out and "I will not do that" in out
    assert out.count("done (") == 3


def test_do_takes_scripted_answers(capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["do", "Go to the table", "--world", "family_home",
                   "--answer", "the dining table", "--json"])
    report = json.loads(capsys.readouterr().out)
    assert status == 0 and report["success"] is True
    assert report["steps"][0]["args"] == {"to": "dining table"}


def test_an_answer_that_does_not_help_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["do", "Go to the table", "--world", "family_home",
                   "--answer", "blue", "--json"])
    assert status == 1
    assert json.loads(capsys.readouterr().out)["success"] is False


def test_chat_rejects_a_bad_question_cost(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(["chat", "--question-cost", "lots"])
    assert exit_.value.code == 2
    assert "a cost from 0 to 10" in capsys.readouterr().err


def test_do_acts_on_the_likeliest_reading_of_what_it_was_told(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["do", "take the cup from the table", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["steps"][0]["args"] == {"to": "kitchen table"}
    assert main(["do", "go to the table", "--json"]) == 1  # no evidence: it asks
    assert main(["do", "go to the table", "--json", "--question-cost", "2"]) == 0
