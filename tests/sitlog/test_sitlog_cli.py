"""``homebot sitlog run|show`` in-process: exit codes and output."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main

A6_INPUTS = ["[day(tuesday)]", "[tuesday,'not ok']", "loop", "tuesday", "[day(monday)]",
             "[monday,ok]", "finish"]


def _inputs() -> list[str]:
    return [argument for line in A6_INPUTS for argument in ("--input", line)]


def test_run_prints_the_history_out_arg_and_globals(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "run", "appendix_a", *_inputs()]) == 0
    out = capsys.readouterr().out
    assert "robot: Good Bye" in out
    assert "main: (is,[tuesday,'not ok']:([day(tuesday)]:" in out
    assert "Out Arg: monday" in out
    assert "Out Global Vars: [g_count_fs1==>1,g_count_fs2==>1]" in out


def test_run_json_and_input_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    inputs = tmp_path / "inputs.txt"
    inputs.write_text("\n".join(A6_INPUTS) + "\n")
    assert main(["sitlog", "run", "appendix_a", "--input-file", str(inputs), "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["out_arg"] == "monday" and result["final"] == "fs"
    assert result["globals"] == {"g_count_fs1": "1", "g_count_fs2": "1"}


def test_run_a_behaviour_on_the_simulated_robot(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "run", "behaviours", "--world", "butler_home",
                 "--call", "find(coke, [shelf_drinks, shelf_snacks], W)"]) == 0
    assert "find: (found(shelf_snacks),empty:shelf_snacks)" in capsys.readouterr().out


def test_running_out_of_input_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "run", "appendix_a", "--json", "--input", "finish:x"]) == 2


def test_show_outline_and_dot(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "show", "appendix_a"]) == 0
    outline = capsys.readouterr().out
    assert "rs [recursive] -> wait" in outline
    assert main(["sitlog", "show", "appendix_a", "--dot"]) == 0
    dot = capsys.readouterr().out
    assert dot.startswith("digraph sitlog {")
    assert "cluster_0" in dot and "cluster_1" in dot
    assert 'xlabel="h"' in dot  # the next situation given by the function h
    assert '"main/rs/1" -> "wait/is/0"' in dot  # the pipe into the embedded model


def test_a_malformed_file_exits_2_with_its_place(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("dialogue_models:\n  - id: main\n    situations:\n"
                   "      - {id: is, type: neutral, arcs: ['empty : empty => nowhere']}\n"
                   "      - {id: fs, type: final}\n")
    assert main(["sitlog", "show", str(bad)]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "bad.yaml, line 4" in err and "unknown next situation 'nowhere'" in err


def test_sitlog_without_a_command_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog"]) == 2


@pytest.mark.parametrize("name", ["appendix_a", "behaviours", "butler"])
def test_every_edge_of_the_diagram_joins_declared_nodes(
        name: str, capsys: pytest.CaptureFixture[str]) -> None:
    import re

    assert main(["sitlog", "show", name, "--dot"]) == 0
    dot = capsys.readouterr().out
    declared = set(re.findall(r'^\s*("[^"]+"|out_arg) \[', dot, re.M))
    edges = re.findall(r'^\s*("[^"]+") -> ("[^"]+"|out_arg)', dot, re.M)
    assert edges
    assert {node for edge in edges for node in edge} <= declared
    assert dot.count("{") == dot.count("}")


def test_the_butler_needs_its_home(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "run", "butler"]) == 2
    assert "homebot scenario butler" in " ".join(capsys.readouterr().err.split())


def test_trace_prints_transitions_as_they_happen(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sitlog", "run", "appendix_a", "--trace", "--input", "finish"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[:2] == ["robot: Good Bye", "  main: (is,finish:screen(Good Bye))"]


def test_speech_asks_a_simulated_person(tmp_path: Path,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "ask.yaml"
    program.write_text("""
dialogue_models:
  - id: main
    situations:
      - id: is
        type: people
        input: "find('Alex', 'living room')"
        arcs: ["found(_) : empty => ask", "error(_) : empty => fs"]
      - id: ask
        type: speech
        input: "'What would you like to drink?'"
        arcs: ["Drink : say(['I will bring you', Drink]) => fs"]
      - {id: fs, type: final}
""")
    assert main(["sitlog", "run", str(program), "--world", "apartment", "--person", "Alex"]) == 0
    assert "say(I will bring you orange juice)" in capsys.readouterr().out
    assert main(["sitlog", "run", str(program), "--person", "Alex"]) == 2
