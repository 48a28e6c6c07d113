"""``homebot ros serve``: a command action with feedback and result, parse, events, speech."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

from homebot.transport.actions import ActionClient, GoalStatus
from homebot.transport.naming import RELIABLE_ALL_QOS
from homebot.transport.node import Node, loopback


@pytest.fixture
def homebot_node(domain_id: int) -> Iterator[int]:
    process = subprocess.Popen(
        [sys.executable, "-c", "import sys; from homebot.cli import main; sys.exit(main())",
         "ros", "serve", "--seed", "2", "--domain-id", str(domain_id)],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    yield domain_id
    process.kill()
    process.wait(10)


def test_a_team_commands_homebot_over_ros2(homebot_node: int) -> None:
    node = Node(loopback(homebot_node))
    events = node.subscription("/homebot/events", "std_msgs/msg/String", RELIABLE_ALL_QOS)
    speech = node.subscription("/homebot/speech", "std_msgs/msg/String")
    parse = node.client("/homebot/parse", "homebot_msgs/srv/Parse")
    assert parse.wait_for_server(60.0)
    reply = parse.call(30.0, command="bring me a cola")
    assert reply.understood and json.loads(reply.steps)[0] == {"skill": "find_object",
                                                               "object": "cola"}
    puzzled = parse.call(30.0, command="blah blah")
    assert not puzzled.understood and "did not understand" in puzzled.error

    command = ActionClient(node, "/homebot/command", "homebot_msgs/action/Command")
    assert command.wait_for_server(60.0)
    assert events.wait_for_publishers(1, 60.0) and speech.wait_for_publishers(1, 60.0)
    goal_id = command.send(30.0, command="bring me a cola")
    assert goal_id is not None
    steps: list[Any] = []
    status, result = command.result(goal_id, 120.0, lambda feedback: steps.append(feedback.step))
    assert status is GoalStatus.SUCCEEDED and result.success
    assert steps[:2] == ["find_object(object=cola)", "pick(object=cola)"]
    said = [message.data for message in speech.take(1000)]
    assert said and said[-1] in result.speech
    kinds = [json.loads(message.data)["kind"] for message in events.take(10_000)]
    assert kinds[0] == "task.start" and kinds[-1] == "task.end" and "skill.start" in kinds
