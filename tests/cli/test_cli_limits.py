"""Limits and depth on the command line: endless files, deep nesting, long listings, big
bounds and names with control characters each end in one clear line."""

from __future__ import annotations

import io
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from homebot.cli import main
from homebot.errors import KnowledgeError
from homebot.files import SIZE_LIMITS
from homebot.text import MOST_LISTED

if TYPE_CHECKING:
    from conftest import FailsCleanly

DATA = Path(__file__).resolve().parents[2] / "src/homebot/data"
JSHOP2 = Path(__file__).resolve().parents[1] / "htn/data/jshop2"


needs_dev_zero = pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")


@needs_dev_zero
@pytest.mark.parametrize(("argv", "limit"), [
    (["world", "check", "/dev/zero"], "2 MiB, the limit for a YAML file"),
    (["world", "map-check", "/dev/zero"], "2 MiB, the limit for a YAML file"),
    (["world", "from-pyrobosim", "/dev/zero", "-o", "{tmp}/w.yaml"],
     "2 MiB, the limit for a YAML file"),
    (["run-task", "/dev/zero"], "2 MiB, the limit for a YAML file"),
    (["kb", "check", "/dev/zero"], "4 MiB, the limit for a KB file"),
    (["plan", "--domain", "/dev/zero", "go"], "4 MiB, the limit for a JSHOP2 file"),
    (["plan", "--domain", str(JSHOP2 / "carts.jshop"), "--problem", "/dev/zero"],
     "4 MiB, the limit for a JSHOP2 file"),
    (["sitlog", "check", "/dev/zero"], "2 MiB, the limit for a dialogue model"),
    (["sitlog", "run", "appendix_a", "--input-file", "/dev/zero"],
     "4 MiB, the limit for a file of inputs"),
    (["golog", "check", "/dev/zero"], "4 MiB, the limit for a Golog program"),
    (["parse", "--file", "/dev/zero"], "4 MiB, the limit for a file of commands"),
    (["listen", "/dev/zero"], "64 MiB, the limit for a WAV file"),
])
def test_an_endless_file_is_refused_at_its_formats_limit(
        argv: list[str], limit: str, tmp_path: Path,
        fails_cleanly: FailsCleanly) -> None:
    argv = [argument.format(tmp=tmp_path) for argument in argv]
    fails_cleanly(main(argv), f"/dev/zero: larger than {limit}")


def test_a_map_image_past_its_limit_is_refused(tmp_path: Path,
                                              fails_cleanly: FailsCleanly) -> None:
    image = tmp_path / "home.pgm"
    with image.open("wb") as handle:  # sparse
        handle.truncate((64 << 20) + 1)
    (tmp_path / "home.yaml").write_text(
        "image: home.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n", encoding="utf-8")
    fails_cleanly(main(["world", "map-check", str(tmp_path / "home.yaml")]),
                  "home.pgm: larger than 64 MiB, the limit for a map image")


def test_a_world_with_a_thousand_problems_lists_the_first_and_counts_the_rest(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # 200,000 duplicate names once printed 21.5 MB of errors
    world = (DATA / "worlds/supermarket.yaml").read_text(encoding="utf-8")
    copies = "".join("  - {name: coke, category: drink, placement: shelf drinks}\n"
                     for _ in range(1_000))
    path = tmp_path / "many.yaml"
    path.write_text(world.replace("people:\n", copies + "people:\n", 1), encoding="utf-8")
    assert main(["world", "check", str(path)]) == 2
    err = capsys.readouterr().err
    lines = err.strip().splitlines()
    assert len(lines) == MOST_LISTED + 1  # each line names the file: its length varies
    assert len(err.replace(str(path), "")) < 3_000
    assert "'coke' is used twice in objects" in lines[0]
    assert lines[-1] == f"... and {1_000 - MOST_LISTED:,} more"


def test_a_long_error_message_of_any_kind_is_capped_when_printed(
        monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    # a message that does not cap its own listing still prints at most a screenful
    problems = [f"odd.kb: problem {number}" for number in range(1_000)]

    def load(_: str) -> None:
        raise KnowledgeError("\n".join(problems))

    monkeypatch.setattr("homebot.cli.kb.KnowledgeBase.load", load)
    assert main(["kb", "check", "odd.kb"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[0] == "error: odd.kb: problem 0"
    assert lines[1:-1] == problems[1:MOST_LISTED + 1]
    assert lines[-1] == f"... and {1_000 - MOST_LISTED - 1:,} more"


@pytest.mark.parametrize("depth", ["100000000", "100001"])
def test_plan_refuses_a_max_depth_past_its_bound(depth: str,
                                                 fails_cleanly: FailsCleanly) -> None:
    # --max-depth 100000000 once took 1.6 GB on a recursive domain
    fails_cleanly(main(["plan", "bring_object", "coke", "Alex", "--max-depth", depth]),
                  f"--max-depth {depth}: at most 100,000")


def test_a_problem_for_another_domain_plans_with_a_note(capsys: pytest.CaptureFixture[str],
                                                        tmp_path: Path) -> None:
    problem = tmp_path / "carts.problem"
    problem.write_text((JSHOP2 / "carts.problem").read_text(encoding="utf-8").replace(
        "(defproblem move_boxes carts", "(defproblem move_boxes trucks"), encoding="utf-8")
    assert main(["plan", "--domain", str(JSHOP2 / "carts.jshop"), "--problem",
                 str(problem)]) == 0
    err = capsys.readouterr().err
    assert (f"note: {problem}:1:1: problem move_boxes is written for domain 'trucks', but the "
            "domain given is 'carts'") in err
    assert main(["plan", "--domain", str(JSHOP2 / "carts.jshop"), "--problem",
                 str(JSHOP2 / "carts.problem")]) == 0
    assert "note:" not in capsys.readouterr().err


def test_kb_names_with_control_characters_are_printed_escaped(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    kb = tmp_path / "odd.kb"
    kb.write_text("[ class(top,none,[],[],[]),\nclass(thing,top,[],[],[\n"
                  "  [id=>'evil\x1b[2J\x1b]0;owned\x07',[[colour=>'red\u202e',0]],[]]\n])\n]\n",
                  encoding="utf-8")
    for argv in (["kb", "query", str(kb), "class_extension", "thing"],
                 ["kb", "query", str(kb), "property_extension", "colour"],
                 ["kb", "explain", str(kb), "evil\x1b[2J\x1b]0;owned\x07"]):
        assert main(argv) == 0
        out = capsys.readouterr().out
        assert "\x1b" not in out and "\x07" not in out and "\u202e" not in out
        assert "\\x1b[2J" in out
    assert main(["kb", "query", str(kb), "property_extension", "colour"]) == 0
    assert "red\\u202e" in capsys.readouterr().out


def test_an_error_quoting_control_characters_prints_them_escaped(
        tmp_path: Path, fails_cleanly: FailsCleanly) -> None:
    err = fails_cleanly(main(["world", "check", str(tmp_path / "no\x1b[2Jworld.yaml")]),
                        "no\\x1b[2Jworld.yaml")
    assert "\x1b" not in err


def test_a_sitlog_arc_50000_deep_is_an_error_with_its_line(
        tmp_path: Path, fails_cleanly: FailsCleanly) -> None:
    depth = 50_000
    model = tmp_path / "deep.yaml"
    model.write_text("dialogue_models:\n  - id: main\n    situations:\n      - id: is\n"
                     "        type: speech\n        arcs:\n"
                     f"          - \"{'f(' * depth}x{')' * depth} : empty => fs\"\n"
                     "      - {id: fs, type: final}\n", encoding="utf-8")
    for command in ("show", "run"):
        fails_cleanly(main(["sitlog", command, str(model)]),
                      f"{model}, line 7, column 214: the term nests deeper than 100 levels")


def test_sitlog_yaml_lists_nested_too_deep_are_an_error(
        tmp_path: Path, fails_cleanly: FailsCleanly) -> None:
    model = tmp_path / "lists.yaml"
    model.write_text("globals: {g: " + "[" * 150 + "]" * 150 + "}\ndialogue_models: []\n",
                     encoding="utf-8")
    fails_cleanly(main(["sitlog", "check", str(model)]),
                  "the lists nest deeper than 100 levels; flatten them")


def test_what_a_dialogue_model_says_is_printed_escaped(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    model = tmp_path / "odd.yaml"
    model.write_text("dialogue_models:\n  - id: main\n    situations:\n      - id: is\n"
                     "        type: neutral\n        arcs:\n"
                     "          - \"empty : say('hi\\x1b[2J there') => fs\"\n"
                     "      - {id: fs, type: final}\n", encoding="utf-8")
    assert main(["sitlog", "run", str(model), "--trace"]) == 0
    out = capsys.readouterr().out
    assert "robot: hi\\x1b[2J there" in out and "\x1b" not in out


@pytest.mark.parametrize("argv", [["chat"], ["do", "--interactive", "ask Alex what time it is"]])
def test_a_typed_line_past_the_text_limit_is_refused(argv: list[str],
                                                     monkeypatch: pytest.MonkeyPatch,
                                                     fails_cleanly: FailsCleanly) -> None:
    # as from /dev/zero: a line with no end (chat < /dev/zero grew 1.8 GB in 20 s)
    monkeypatch.setattr(sys, "stdin", io.StringIO("a" * (SIZE_LIMITS["text"] + 10)))
    fails_cleanly(main(argv), "<stdin>: a line longer than 4 MiB, the limit for one "
                  "typed line")


def test_chat_reads_piped_lines_within_the_limit(monkeypatch: pytest.MonkeyPatch,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "stdin", io.StringIO("go to the kitchen\nquit\n"))
    assert main(["chat"]) == 0
    assert "done" in capsys.readouterr().out
