"""Bad input of the robot's body: a robot in a wall or furniture, a zero speed limit,
a point goal that cannot be reached, a map that does not match its YAML. Exit 2, one line."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from homebot.cli import main

if TYPE_CHECKING:
    from conftest import FailsCleanly

SUPERMARKET = Path(__file__).resolve().parents[2] / "src/homebot/data/worlds/supermarket.yaml"
START = "pose: [1.5, 1.5, 0.0]"


def _file(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _supermarket(tmp_path: Path, robot: str) -> Path:
    text = SUPERMARKET.read_text(encoding="utf-8")
    assert START in text
    return _file(tmp_path, "w.yaml", text.replace(START, robot, 1))


@pytest.mark.parametrize(("robot", "expected"), [
    ("pose: [5.0, 0.5, 0.0]", "robot.pose: the robot at (5, 0.5) is inside the shelf bread"),
    ("pose: [5.0, 1.0, 0.0]", "is 0.20 m from the shelf bread, closer than the robot's radius"),
    ("pose: [10.0, 3.0, 0.0]", "robot.pose: the robot at (10, 3) is inside a wall"),
    ("pose: [0.2, 4.0, 0.0]", "is 0.15 m from a wall"),
    ("pose: [20.0, 3.0, 0.0]", "is outside every room"),
])
def test_a_robot_placed_in_a_wall_or_furniture_exits_2(
        tmp_path: Path, robot: str, expected: str, fails_cleanly: FailsCleanly) -> None:
    world = _supermarket(tmp_path, robot)
    fails_cleanly(main(["world", "check", str(world)]), expected)
    task = _file(tmp_path, "t.yaml", "- {skill: say, text: hello}\n")
    fails_cleanly(main(["run-task", str(task), "--world", str(world)]), expected)


def test_a_robot_in_a_door_opening_is_fine(tmp_path: Path,
                                           capsys: pytest.CaptureFixture[str]) -> None:
    world = _supermarket(tmp_path, "pose: [10.0, 6.0, 0.0]")
    assert main(["world", "check", str(world)]) == 0
    assert "ok" in capsys.readouterr().out


@pytest.mark.parametrize(("robot", "expected"), [
    (START + "\n  speed: 0", "robot.speed: must be greater than 0 (got 0); speed is the base's "
                             "top linear speed, in m/s"),
    (START + "\n  angular_speed: 0", "robot.angular_speed: must be greater than 0 (got 0); "
                                     "angular_speed is the base's top turning speed, in rad/s"),
    (START + "\n  speed: -0.5", "robot.speed: must be greater than 0 (got -0.5)"),
])
def test_a_velocity_limit_of_zero_exits_2(tmp_path: Path, robot: str, expected: str,
                                          fails_cleanly: FailsCleanly) -> None:
    world = _supermarket(tmp_path, robot)
    err = fails_cleanly(main(["world", "check", str(world)]), expected)
    assert "line 42" in err


def test_world_map_writes_a_pair_that_map_check_reads(tmp_path: Path,
                                                      capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["world", "map", "--world", "supermarket", "-o", str(tmp_path / "maps")]) == 0
    assert "supermarket.yaml" in capsys.readouterr().out
    yaml_path = tmp_path / "maps" / "supermarket.yaml"
    assert (tmp_path / "maps" / "supermarket.pgm").exists()
    assert main(["world", "map-check", str(yaml_path), "--world", "supermarket"]) == 0
    out = capsys.readouterr().out
    assert "288×168 cells at 0.05 m, origin (-0.2, -0.2, 0)" in out
    assert "covers world 'supermarket', free floor differs in 0 cells" in out
    assert main(["world", "map-check", str(yaml_path), "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    assert figures["width"] == 288 and figures["height"] == 168
    assert figures["free"] + figures["occupied"] + figures["unknown"] == 288 * 168
    assert figures["occupied"] > 0 and figures["unknown"] > 0


@pytest.mark.parametrize(("change", "expected"), [
    (("image: supermarket.pgm", "image: missing.pgm"), "image: the image"),
    (("resolution: 0.05", "resolution: 0"), "resolution: must be greater than 0"),
    (("origin: [-0.2, -0.2, 0.0]\n", ""), "'origin' is missing"),
    (("mode: trinary", "mode: fuzzy"), "unknown mode 'fuzzy'"),
    (("negate: 0", "negate: [0"), "YAML syntax error"),
])
def test_a_map_that_does_not_match_its_yaml_exits_2(
        tmp_path: Path, change: tuple[str, str], expected: str,
        capsys: pytest.CaptureFixture[str],
        fails_cleanly: FailsCleanly) -> None:
    assert main(["world", "map", "--world", "supermarket", "-o", str(tmp_path)]) == 0
    capsys.readouterr()
    yaml_path = tmp_path / "supermarket.yaml"
    yaml_path.write_text(yaml_path.read_text(encoding="utf-8").replace(*change),
                         encoding="utf-8")
    err = fails_cleanly(main(["world", "map-check", str(yaml_path)]), expected)
    assert str(yaml_path) in err


def test_a_map_too_small_for_the_world_exits_2(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str],
        fails_cleanly: FailsCleanly) -> None:
    assert main(["world", "map", "--world", "supermarket", "-o", str(tmp_path)]) == 0
    capsys.readouterr()
    status = main(["world", "map-check", str(tmp_path / "supermarket.yaml"),
                   "--world", "apartment"])
    fails_cleanly(status, "but world 'apartment' spans x 0..12, y 0..10 m")


def test_a_broken_map_image_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str],
        fails_cleanly: FailsCleanly) -> None:
    assert main(["world", "map", "--world", "supermarket", "-o", str(tmp_path)]) == 0
    capsys.readouterr()
    (tmp_path / "supermarket.pgm").write_bytes(b"P5\n288 168\n255\n" + bytes(100))
    fails_cleanly(main(["world", "map-check", str(tmp_path / "supermarket.yaml")]),
                  "check it is a complete PGM file")


@pytest.mark.parametrize(("to", "expected"), [
    ("[5.0, 0.5]", "step 2: navigate.to (5, 0.5) is inside the shelf bread"),
    ("{x: 5.0, y: 0.5}", "step 2: navigate.to (5, 0.5) is inside the shelf bread"),
    ("[10.0, 3.0]", "step 2: navigate.to (10, 3) is inside a wall"),
    ("[20, 3]", "step 2: navigate.to (20, 3) is outside every room"),
    ("[5.0, 1.0]", "is 0.20 m from the shelf bread, closer than the robot's radius 0.25 m"),
    ("[1, 2, 3]", "navigate.to is a name or a point [x, y] / {x: X, y: Y}, not [1, 2, 3]"),
    ("{x: 1}", "a point is {x: X, y: Y}, not keys ['x']"),
    ("[1, .nan]", "a point's x and y are finite numbers"),
    ("[true, 2]", "a point's x and y are finite numbers"),
])
def test_a_point_goal_where_the_robot_cannot_stand_exits_2(
        tmp_path: Path, to: str, expected: str, fails_cleanly: FailsCleanly) -> None:
    task = _file(tmp_path, "t.yaml", "- {skill: say, text: hello}\n"
                                     f"- {{skill: navigate, to: {to}}}\n")
    status = main(["run-task", str(task), "--world", str(SUPERMARKET)])
    err = fails_cleanly(status, expected)
    assert "t.yaml: line 2: step 2" in err


@pytest.mark.parametrize("to", ["[12.0, 2.0]", "{x: 12.0, y: 2.0}"])
def test_a_point_goal_on_free_floor_is_driven_to(tmp_path: Path, to: str,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    events = tmp_path / "events.jsonl"
    task = _file(tmp_path, "t.yaml", f"- {{skill: navigate, to: {to}}}\n")
    status = main(["run-task", str(task), "--world", str(SUPERMARKET), "--json",
                   "--events", str(events)])
    assert status == 0, capsys.readouterr()
    report = json.loads(capsys.readouterr().out)
    assert report["steps"][0]["status"] == "verified"
    log = events.read_text(encoding="utf-8")
    assert "I am at the point (12, 2)" in log
    path = [json.loads(line) for line in log.splitlines() if '"robot.path"' in line]
    assert path and path[-1]["points"][-1] == pytest.approx([12.0, 2.0], abs=0.05)
