"""``homebot parse`` and ``homebot world from-robocup`` in-process: exit codes and output."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from homebot.cli import main
from homebot.world import World


def test_parse_json_ok(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["parse", "Go to the kitchen", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == {
        "status": "ok", "steps": [{"skill": "navigate", "to": "kitchen"}]}


def test_parse_clarify_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["parse", "Bring me the drink"]) == 1
    assert capsys.readouterr().out.startswith("clarify:")


def test_parse_reject_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["parse", "Fetch the kitchen", "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["status"] == "reject"


def test_parse_empty_command_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["parse", "  "]) == 2
    assert "empty" in capsys.readouterr().err


def test_parse_unknown_world_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["parse", "Go to the kitchen", "--world", "mars"]) == 2


def test_parse_file_one_json_a_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    commands = tmp_path / "commands.txt"
    commands.write_text("Go to the kitchen\n\nBring me the drink\n", encoding="utf-8")
    assert main(["parse", "--file", str(commands)]) == 1
    lines = [json.loads(line) for line in capsys.readouterr().out.splitlines()]
    assert [line["status"] for line in lines] == ["ok", "clarify"]


def test_parse_needs_a_command_or_a_file() -> None:
    assert main(["parse"]) == 2


def test_world_from_robocup_writes_a_valid_world(tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    data = tmp_path / "data"
    for name, text in {
        "names/names.md": "| Names |\n| --- |\n| Ada |\n",
        "maps/room_names.md": "| Name |\n| --- |\n| kitchen |\n| hall |\n",
        "maps/location_names.md": "| N | Name | Category |\n| - | - | - |\n"
                                  "| 1 | fridge (p) | drinks |\n| 2 | bed (p) |\n",
        "objects/objects.md": "# Class drinks (drink)\n| Objectname | Image |\n|:-:|:-:|\n"
                              "| cola | ![](x.png) |\n",
    }.items():
        (data / name).parent.mkdir(parents=True, exist_ok=True)
        (data / name).write_text(text, encoding="utf-8")
    output = tmp_path / "world.yaml"
    assert main(["world", "from-robocup", str(data), "-o", str(output)]) == 0
    world = World.load(output)
    assert set(world.placements) == {"fridge", "bed"} and "cola" in world.objects


def test_world_from_robocup_bad_directory_exits_2(tmp_path: Path) -> None:
    assert main(["world", "from-robocup", str(tmp_path / "none"), "-o",
                 str(tmp_path / "w.yaml")]) == 2
