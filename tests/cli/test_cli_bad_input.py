"""Trying to break the command line: odd files, types and options give exit 2, one line."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from homebot.cli import main

if TYPE_CHECKING:
    from conftest import FailsCleanly

SUPERMARKET = Path(__file__).resolve().parents[2] / "src/homebot/data/worlds/supermarket.yaml"
FETCH = "- {skill: find_object, object: drink}\n- {skill: pick, object: drink}\n"


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(("task", "expected"), [
    ("- {skill: navigate, to: kitchen, 1: x}\n", "argument names are words, not 1"),
    ("{1: a, b: c}\n", "unknown field '1'"),
    ("- {skill: navigate, to: [kitchen]}\n",
     "navigate.to is a name or a point [x, y] / {x: X, y: Y}, not ['kitchen']"),
    ("- {skill: guide, to: [1, 2]}\n", "guide.to is a name or text, not [1, 2]"),
    ("- {skill: say, text: {a: 1}}\n", "say.text is a name or text"),
    ("- {skill: find_person, person: {name: [1]}}\n", "find_person.person.name is a word"),
    ("- {skill: find_person, person: {1: x}}\n", "not '1'"),
    ("- {skill: find_person, person: {name: ''}}\n", "find_person.person.name is a word"),
    ("- {skill: pick, object: cola, hand: 3}\n",
     "pick.hand is one of the robot's hands (left, right), not 3"),
    ("- {skill: find_object, object: cola, exclude: [window]}\n", "unknown placement 'window'"),
    ("- {skill: navigate, to: $kitchen}\n", "unknown target '$kitchen'"),
    ("- {skill: navigate, to: '[/bold]x'}\n", "unknown target '[/bold]x'"),
    ("a: " + "[" * 3000 + "]" * 3000 + "\n", "nested too deeply"),
    ("- {skill: navigate, to: kitchen, to: office}\n", "line 1: 'to' appears twice"),
    ("- {skill: navigate, to: kitchen}\n" * 1_001,
     "line 1001: 1,001 steps, more than the 1,000 a task may have; split it"),
])
def test_odd_task_files_exit_2(tmp_path: Path, task: str, expected: str,
                               fails_cleanly: FailsCleanly) -> None:
    status = main(["run-task", str(_file(tmp_path, "task.yaml", task))])
    fails_cleanly(status, expected)


def test_binary_and_directory_task_files_exit_2(tmp_path: Path,
                                                fails_cleanly: FailsCleanly) -> None:
    binary = tmp_path / "task.yaml"
    binary.write_bytes(bytes(range(256)))
    fails_cleanly(main(["run-task", str(binary)]), "give a UTF-8 text file")
    fails_cleanly(main(["run-task", str(tmp_path)]), "cannot read it")


def test_speech_with_markup_is_printed_as_said(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    task = _file(tmp_path, "task.yaml", "- {skill: say, text: '[/x] [bold]hi'}\n")
    assert main(["run-task", str(task)]) == 0
    assert "[/x] [bold]hi" in capsys.readouterr().out


@pytest.mark.parametrize(("old", "new", "expected"), [
    ("[[0, 0], [10, 0], [10, 8], [0, 8]]", "[[0, 0], [10, 8], [10, 0], [0, 8]]",
     "polygon is not a simple area"),
    ("[[0, 0], [10, 0], [10, 8], [0, 8]]", "[[0, 0], [.nan, 0], [10, 8], [0, 8]]",
     "finite number"),
    ("pose: [1.5, 1.5, 0.0]", "pose: [1.5, 1.5, .inf]", "robot.pose.2"),
    ("operator: customer", "operator: customer\nrooms: []", "'rooms' appears twice"),
    ("[[10, 0], [14, 0], [14, 8], [10, 8]]", "[[10, 0], [5000, 0], [5000, 5000], [10, 5000]]",
     "use a coarser grid_resolution"),
])
def test_odd_worlds_exit_2(tmp_path: Path, old: str, new: str, expected: str,
                           capsys: pytest.CaptureFixture[str]) -> None:
    text = SUPERMARKET.read_text(encoding="utf-8")
    assert old in text
    world = _file(tmp_path, "w.yaml", text.replace(old, new, 1))
    status = main(["world", "check", str(world)])
    captured = capsys.readouterr()
    assert status == 2 and expected in captured.err and "Traceback" not in captured.err


@pytest.mark.parametrize("argv", [
    ["do", "go to the kitchen", "--disturb", "-1"],
    ["do", "go to the kitchen", "--disturb", "nan"],
    ["run-task", "task.yaml", "--disturb", "1e9"],
    ["scenario", "fetch", "--level", "50"],
    ["scenario", "jenny", "--slip", "7"],
    ["bench", "robustness", "--level", "x"],
])
def test_out_of_range_levels_are_usage_errors(argv: list[str],
                                              capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    assert "is a number from 0 to" in capsys.readouterr().err


def test_world_show_png_to_bad_places_exits_2(tmp_path: Path,
                                              fails_cleanly: FailsCleanly) -> None:
    status = main(["world", "show", "--png", str(tmp_path / "map.txt")])
    fails_cleanly(status, "give a name ending in .png")
    status = main(["world", "show", "--png", str(tmp_path / "no" / "map.png")])
    fails_cleanly(status, "check that its folder exists")
    events = _file(tmp_path, "events.jsonl", "[1]\n")
    status = main(["world", "show", "--png", str(tmp_path / "m.png"), "--events", str(events)])
    fails_cleanly(status, "not a homebot event log")


def test_events_to_a_bad_place_exit_2(tmp_path: Path,
                                      fails_cleanly: FailsCleanly) -> None:
    task = _file(tmp_path, "task.yaml", FETCH)
    status = main(["run-task", str(task), "--events", str(tmp_path)])
    fails_cleanly(status, "cannot write the event log")


def test_same_seed_same_event_log(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    task = str(_file(tmp_path, "task.yaml", FETCH))
    command = "find a fruit in the kitchen then get it and deliver it to me"
    logs = []
    for name in ("a", "b"):
        for argv in (["run-task", task], ["do", command]):
            events = tmp_path / f"{argv[0]}-{name}.jsonl"
            main([*argv, "--disturb", "1", "--seed", "7", "--events", str(events)])
            logs.append(events.read_text(encoding="utf-8"))
    assert logs[0] == logs[2] and logs[1] == logs[3]
    assert logs[0] and logs[1]


def test_demo_in_a_world_without_its_names_exits_2(fails_cleanly: FailsCleanly) -> None:
    status = main(["demo", "--world", "supermarket", "--quiet"])
    fails_cleanly(status, "the demo is written for the apartment")


def test_parse_file_names_the_line_it_cannot_take(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    commands = _file(tmp_path, "commands.txt", "Go to the kitchen\n" + "x " * 800 + "\n")
    status = main(["parse", "--file", str(commands)])
    captured = capsys.readouterr()
    assert status == 2 and "commands.txt: line 2: the command has 1600 characters" in captured.err


_LAUGHS = "[" + ", ".join(["&a [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
                          + [f"&{b} [{', '.join([f'*{a}'] * 9)}]"
                             for a, b in zip("abcdefg", "bcdefgh", strict=True)]) + "]"


@pytest.mark.parametrize(("task", "expected"), [
    (f"- {{skill: say, text: {_LAUGHS}}}\n", "say.text is a name or text"),
    (f"description: {_LAUGHS}\nsteps: [{{skill: say, text: hi}}]\n", "description is one line"),
])
def test_nested_aliases_give_a_short_message(tmp_path: Path, task: str, expected: str,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    status = main(["run-task", str(_file(tmp_path, "task.yaml", task))])
    err = capsys.readouterr().err
    assert status == 2 and expected in err and len(err) < 400


def test_a_world_of_nested_aliases_gives_a_short_message(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    world = _file(tmp_path, "w.yaml", f"name: x\nrooms: {_LAUGHS}\nrobot: {{pose: [0, 0, 0]}}\n")
    assert main(["world", "check", str(world)]) == 2
    err = capsys.readouterr().err
    assert "rooms.0" in err and len(err) < 2000


def test_world_without_a_command_names_all_three(fails_cleanly: FailsCleanly) -> None:
    fails_cleanly(main(["world"]), "from-robocup DIR")


def test_an_approach_pose_outside_the_room_exits_2(tmp_path: Path,
                                                   fails_cleanly: FailsCleanly) -> None:
    text = SUPERMARKET.read_text(encoding="utf-8").replace(
        "holds: [drink]", "approach: [50, 50, 0], holds: [drink]")
    status = main(["world", "check", str(_file(tmp_path, "w.yaml", text))])
    fails_cleanly(status, "placements.1.approach: [50.0, 50.0] lies outside room")


@pytest.mark.parametrize("argv", [
    ["do", "go to the kitchen"], ["run-task", "task.yaml"], ["scenario", "fetch"],
    ["serve"], ["sim", "serve"], ["sitlog", "run", "model.yaml"], ["bench", "fetch"],
])
def test_a_negative_seed_is_refused_everywhere(argv: list[str],
                                               fails_cleanly: FailsCleanly) -> None:
    # random.Random(-1) plays as Random(1): -1 must not silently repeat seed 1
    fails_cleanly(main([*argv, "--seed", "-1"]), "--seed '-1': give a whole number")


def _usage_error(capsys: pytest.CaptureFixture[str], argv: list[str]) -> str:
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    return capsys.readouterr().err.strip().splitlines()[-1]


@pytest.mark.parametrize(("argv", "expected"), [
    (["run-task", "t.yaml", "--robot", "ros", "--connect-timeout", "-1"],
     "argument --connect-timeout: a time to wait is more than 0 seconds and at most 3600, "
     "not '-1'"),
    (["run-task", "t.yaml", "--robot", "ros", "--connect-timeout", "nan"],
     "argument --connect-timeout: a time to wait"),
    (["run-task", "t.yaml", "--robot", "ros", "--connect-timeout", "0"],
     "more than 0 seconds"),
    (["serve", "--host", "999.1.1.1"], "argument --host: '999.1.1.1' is no IP address; give"),
    (["serve", "--host", "192.0.2.1"], "argument --host: '192.0.2.1' is not an address of "
                                       "this machine"),
    (["serve", "--walkers", "-1"], "argument --walkers"),
    (["sim", "serve", "--crash-after", "-3"], "argument --crash-after"),
])
def test_out_of_range_options_are_usage_errors(argv: list[str], expected: str,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    assert expected in _usage_error(capsys, argv)


def test_a_host_of_this_machine_is_taken() -> None:
    from homebot.cli import command_line_argument_parser

    args = command_line_argument_parser().parse_args(["serve", "--host", "127.0.0.1"])
    assert args.host == "127.0.0.1"


@pytest.mark.parametrize(("log", "expected"), [
    ('{"kind": "robot.path", "world": "apartment", "points": [[NaN, 1]]}\n',
     "line 1: not a homebot event log (NaN is no number)"),
    ('{"kind": "sim.speech"}\n{"kind": "robot.path", "world": "apartment", '
     '"points": [[1e300, 1]]}\n', "line 2: robot.path point [1e+300, 1] lies 1e+300 m outside"),
    ('{"kind": "robot.path", "world": "apartment", "points": [[1, 1e999]]}\n',
     "1e999 is too large a number"),
    ('{"kind": "sim.final", "world": "apartment", "robot": [2, 3, 0], '
     '"people": {"Alex": [-40, 2]}}\n', "sim.final point [-40, 2] lies 40 m outside"),
    ('{"kind": "robot.path", "world": "apartment", "points": [["a", 1]]}\n',
     "not a point [x, y]"),
])
def test_world_show_refuses_event_logs_with_points_off_the_map(
        tmp_path: Path, log: str, expected: str, fails_cleanly: FailsCleanly) -> None:
    events = _file(tmp_path, "events.jsonl", log)
    status = main(["world", "show", "--png", str(tmp_path / "m.png"), "--events", str(events)])
    fails_cleanly(status, expected)
    assert not (tmp_path / "m.png").exists()


def test_world_show_events_needs_a_file_and_a_map(tmp_path: Path,
                                                 fails_cleanly: FailsCleanly) -> None:
    missing = str(tmp_path / "missing.jsonl")
    fails_cleanly(main(["world", "show", "--png", str(tmp_path / "m.png"),
                  "--events", missing]), "missing.jsonl: no such file")
    fails_cleanly(main(["world", "show", "--events", missing]),
                  "the run is drawn on the map; give --png")


def test_world_show_draws_a_run_of_this_world(tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    events = _file(tmp_path, "events.jsonl",
                   '{"kind": "robot.path", "world": "apartment", "points": [[2, 2], [3, 2]]}\n'
                   '{"kind": "robot.path", "world": "elsewhere", "points": [[1e300, 2]]}\n')
    status = main(["world", "show", "--png", str(tmp_path / "m.png"), "--events", str(events)])
    assert status == 0 and (tmp_path / "m.png").stat().st_size > 0
