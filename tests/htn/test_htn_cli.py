"""``homebot plan`` and ``homebot do --planner htn``, in-process."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main

DOMAIN = """\
(defdomain lights
  ((:operator (!switch_on ?l) ((off ?l)) ((off ?l)) ((on ?l)))
   (:method (light_up ?l) done ((on ?l)) nil go () ((!switch_on ?l)))))
"""
PROBLEM = "(defproblem evening lights ((off lamp) (off desk_lamp)) ((light_up lamp)))\n"
PYTHON_DOMAIN = """\
from homebot.htn import Domain

def domain():
    made = Domain("python_lights")
    made.operator(("!switch_on", "?l"), [("off", "?l")], [("off", "?l")], [("on", "?l")])
    return made
"""


def _file(tmp_path: Path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_plan_prints_the_task_network(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "bring_object", "pringles", "Alex", "--all"]) == 0
    out = capsys.readouterr().out
    assert "3 plans for (bring_object robot pringles Alex); shortest 8 operators" in out
    assert "(fetch robot pringles)  [where-told]" in out
    assert "   8. (!report robot bring pringles Alex)" in out


def test_plan_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "guide_person", "Alex", "bedroom", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert list(data) == ["plans"] and len(data["plans"]) == 1
    assert data["plans"][0][1] == {"operator": "!move_base",
                                   "args": ["robot", "entrance", "living room"]}
    assert main(["plan", "bring_object", "pringles", "operator", "--all", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["plans"]) == 3


def test_plan_dot(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "tidy", "--dot"]) == 0
    out = capsys.readouterr().out
    assert out.startswith('digraph "tidy robot"') and "shape=box" in out and out.endswith("}\n")


def test_plan_with_a_jshop_domain_and_problem(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    domain = _file(tmp_path, "lights.jshop", DOMAIN)
    problem = _file(tmp_path, "evening.jshop", PROBLEM)
    assert main(["plan", "--domain", domain, "--problem", problem, "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == {
        "plans": [[{"operator": "!switch_on", "args": ["lamp"]}]]}
    assert main(["plan", "light_up", "desk_lamp", "--domain", domain, "--problem", problem,
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["plans"][0][0]["args"] == ["desk_lamp"]
    assert main(["plan", "light_up", "attic", "--domain", domain, "--problem", problem]) == 1
    assert "no plan" in capsys.readouterr().out


def test_plan_with_a_python_domain(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    domain = _file(tmp_path, "lights.py", PYTHON_DOMAIN)
    problem = _file(tmp_path, "evening.jshop", PROBLEM.replace("light_up", "!switch_on"))
    assert main(["plan", "--domain", domain, "--problem", problem, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["plans"][0] == [
        {"operator": "!switch_on", "args": ["lamp"]}]
    broken = _file(tmp_path, "broken.py", "def domain():\n    return 1 / 0\n")
    assert main(["plan", "x", "--domain", broken]) == 2
    assert "ZeroDivisionError" in capsys.readouterr().err


@pytest.mark.parametrize(("argv", "words"), [
    (["plan", "bring_object", "pringels", "Alex"], "did you mean 'pringles'"),
    (["plan", "bring_objekt", "pringles", "Alex"], "did you mean 'bring_object'"),
    (["plan", "guide_person", "Alex"], "takes 2 arguments"),
    (["plan"], "give a TASK"),
    (["plan", "bring_object", "pringles", "Alex", "--all", "--limit", "0"], "1 or more"),
])
def test_plan_errors_exit_2(argv: list[str], words: str,
                            capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err


def test_plan_reports_bad_domain_files_with_their_place(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = _file(tmp_path, "bad.jshop", "(defdomain d (\n  (:operator (!a) () ())))")
    assert main(["plan", "x", "--domain", bad]) == 2
    assert f"{bad}:2:3:" in capsys.readouterr().err


def test_do_with_the_htn_planner(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["do", "bring me the pringles", "--planner", "htn", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["success"] is True and data["goals"] == [["serve", "robot", "pringles", "Alex"]]
    assert [op["status"] for op in data["runs"][0]["operators"]] == ["verified"] * 8
    assert main(["do", "guide Alex from the couch to the bedroom", "--planner", "htn"]) == 0
    assert "(!guide robot Alex bedroom) -> guide" in capsys.readouterr().out


def test_do_falls_back_to_the_parsed_steps(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["do", "tell me the time", "--planner", "htn"]) == 0
    captured = capsys.readouterr()
    assert "no task for this command" in captured.err and "robot:" in captured.out


def test_plan_trace(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "guide_person", "Alex", "bedroom", "--trace"]) == 0
    out = capsys.readouterr().out
    assert "(go_to robot living_room): there does not apply" in out
