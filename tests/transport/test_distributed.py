"""homebot over ROS 2 in two processes: ``homebot sim serve`` and the executive here.

The fetch task must give the same event log as in-process; a killed simulator must be
reported as a lost robot, and a restarted one picked up again.
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

from homebot.cli import main
from homebot.transport.node import Node, loopback
from homebot.transport.ros_robot import RobotLost, RosRobot

TASK = """\
description: bring the cola
steps:
  - {skill: navigate, to: fridge}
  - {skill: find_object, object: cola, placement: fridge}
  - {skill: pick, object: cola}
  - {skill: navigate, to: operator}
  - {skill: give, person: operator}
"""


@pytest.fixture
def simulator() -> Iterator[Callable[..., subprocess.Popen[bytes]]]:
    started: list[subprocess.Popen[bytes]] = []

    def start(domain_id: int, *options: str) -> subprocess.Popen[bytes]:
        process = subprocess.Popen(
            [sys.executable, "-c", "import sys; from homebot.cli import main; sys.exit(main())",
             "sim", "serve", "--domain-id",
             str(domain_id), *options], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        started.append(process)
        return process

    yield start
    for process in started:
        process.kill()
        process.wait(10)


@pytest.mark.parametrize("seed", [0, 4])
def test_a_fetch_over_ros2_logs_what_it_logs_in_process(
        tmp_path: Path, domain_id: int, seed: int,
        simulator: Callable[..., subprocess.Popen[bytes]]) -> None:
    task = tmp_path / "task.yaml"
    task.write_text(TASK, encoding="utf-8")
    here, there = tmp_path / "in_process.jsonl", tmp_path / "over_ros.jsonl"
    options = ["--seed", str(seed), "--disturb", "1"]
    in_process = main(["run-task", str(task), "--json", "--events", str(here), *options])
    simulator(domain_id, *options)
    over_ros = main(["run-task", str(task), "--json", "--events", str(there), *options,
                     "--robot", "ros", "--domain-id", str(domain_id)])
    assert over_ros == in_process
    assert there.read_text(encoding="utf-8") == here.read_text(encoding="utf-8")
    assert '"kind": "sim.final"' in there.read_text(encoding="utf-8")


def test_a_killed_simulator_is_a_lost_robot_and_a_restarted_one_is_picked_up(
        domain_id: int, simulator: Callable[..., subprocess.Popen[bytes]]) -> None:
    robot = RosRobot(Node(loopback(domain_id)))
    process = simulator(domain_id)
    robot.connect(30.0)
    before = robot.pose()
    process.kill()
    process.wait(10)
    with pytest.raises(RobotLost):
        robot.perceive_people()
    simulator(domain_id)
    robot.connect(30.0)
    assert robot.pose() == before  # the same world and seed: it starts where it started
    assert robot.say("hello") is None


def test_run_task_tells_the_operator_when_no_robot_answers(
        tmp_path: Path, domain_id: int, capsys: pytest.CaptureFixture[str]) -> None:
    task = tmp_path / "task.yaml"
    task.write_text(TASK, encoding="utf-8")
    status = main(["run-task", str(task), "--robot", "ros", "--domain-id", str(domain_id),
                   "--connect-timeout", "0.5"])
    assert status == 2
    assert "no robot answers on ROS 2 domain" in capsys.readouterr().err


def test_a_simulator_that_dies_mid_task_ends_the_task_with_the_operator_told(
        tmp_path: Path, domain_id: int, simulator: Callable[..., subprocess.Popen[bytes]],
        capsys: pytest.CaptureFixture[str]) -> None:
    task = tmp_path / "task.yaml"
    task.write_text(TASK, encoding="utf-8")
    events = tmp_path / "events.jsonl"
    crashed = simulator(domain_id, "--crash-after", "6")  # dies after the first navigation
    status = main(["run-task", str(task), "--robot", "ros", "--domain-id", str(domain_id),
                   "--events", str(events)])
    assert crashed.wait(10) == 3
    assert status == 1
    assert "lost contact with the robot" in capsys.readouterr().out
    kinds = [json.loads(line)["kind"] for line in events.read_text(encoding="utf-8").split("\n")
             if line]
    assert kinds[-2:] == ["robot.lost", "task.end"] and "skill.start" in kinds
    simulator(domain_id)  # restarted: the next task runs on it
    assert main(["run-task", str(task), "--robot", "ros", "--domain-id", str(domain_id)]) == 0
