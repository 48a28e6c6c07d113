"""Every server survives every message: the cases issue 33 found, then a seeded fuzz.

``homebot ros serve`` and ``homebot sim serve`` run as their own processes on loopback, as a
team's stack would reach them. Each bad request must get an error answer (and a log line,
never a traceback), and the server must go on answering, its memory flat.
"""

from __future__ import annotations

import json
import math
from typing import Any

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

from homebot.bench.serve_fuzz import FuzzReport, fuzz_server
from homebot.geometry import Pose
from homebot.transport.actions import ActionClient, GoalStatus
from homebot.transport.messages import pose_stamped


def _ros_serve_cases(node: Any) -> None:
    """Issue 33: an empty or over-long parse request, an empty command goal."""
    parse = node.client("/homebot/parse", "homebot_msgs/srv/Parse")
    command = ActionClient(node, "/homebot/command", "homebot_msgs/action/Command")
    assert parse.wait_for_server(30.0) and command.wait_for_server(30.0)
    empty = parse.call(30.0, command="")
    assert not empty.understood and "the command is empty" in empty.error
    overlong = parse.call(30.0, command="bring " * 400)
    assert not overlong.understood
    assert "has 2400 characters; keep it under 1000" in overlong.error
    goal_id = command.send(30.0, command="")
    assert goal_id is not None
    status, result = command.result(goal_id, 30.0)
    assert status is GoalStatus.ABORTED and not result.success
    assert "/homebot/command: the command is empty" in result.reason
    assert parse.call(30.0, command="bring me a cola").understood


def _sim_serve_cases(node: Any) -> None:
    """Issue 33: ``move_options`` with ``[1]``, 6 kB of nested JSON; an unknown method, and
    navigation goals that are not finite, outside the map or in another frame."""
    calls = node.client("/homebot/robot", "homebot_msgs/srv/RobotCall")
    assert calls.wait_for_server(30.0)

    def error_of(method: str, arguments: str) -> str:
        result = json.loads(calls.call(30.0, method=method, arguments=arguments).result)
        assert isinstance(result, dict) and set(result) == {"error"}, result
        return str(result["error"])

    assert "move_options: malformed arguments: (arguments): Input should be an object" in \
        error_of("move_options", "[1]")
    assert "recursion limit exceeded" in error_of("say", '{"text": ' + "[" * 6000)
    assert "no method 'fly'" in error_of("fly", "{}")
    assert "now: Extra inputs are not permitted" in error_of("final_state", '{"now": 1}')
    pose = json.loads(calls.call(30.0, method="pose", arguments="{}").result)
    assert set(pose) == {"x", "y", "theta"}
    navigate = ActionClient(node, "/navigate_to_pose", "nav2_msgs/action/NavigateToPose")
    assert navigate.wait_for_server(30.0)
    for x, frame in ((math.nan, "map"), (1e308, "map"), (pose["x"], "odom")):
        goal = pose_stamped(node.types, Pose(x, pose["y"], 0.0), 0.0, frame)
        goal_id = navigate.send(30.0, pose=goal)
        assert goal_id is not None and navigate.result(goal_id, 30.0)[0] is GoalStatus.ABORTED
    goal_id = navigate.send(30.0, pose=pose_stamped(node.types, Pose(**pose), 0.0))
    assert goal_id is not None and navigate.result(goal_id, 30.0)[0] is GoalStatus.SUCCEEDED


@pytest.mark.parametrize(("name", "cases"), [("ros serve", _ros_serve_cases),
                                             ("sim serve", _sim_serve_cases)])
def test_a_server_answers_every_malformed_request_and_goes_on(
        name: str, cases: Any, domain_id: int) -> None:
    report: FuzzReport = fuzz_server(name, requests=400, seed=7, domain_id=domain_id,
                                     warm_up=100, oversized=5, time_limit=120, first=cases)
    assert report.requests == 400 and report.unanswered == 0
    assert report.answered + report.dropped_by_dds == 400 and report.dropped_by_dds > 0
    assert report.alive and report.valid_answer and report.internal_errors == 0
    assert report.log_lines >= report.answered // 2  # refused requests are logged
    assert report.rss_end_mb - report.rss_start_mb < 5.0


class _UnreadableReader:
    """A reader whose samples cannot be decoded (what a raw RTPS writer could send: bytes
    that are not the type's CDR); typed DDS writers cannot, XTypes refuses to match them."""

    def __init__(self, error: Exception) -> None:
        self.error = error

    def take(self, N: int) -> list[Any]:  # N: cyclonedds' own argument name
        raise self.error


def test_an_unreadable_sample_is_dropped_and_logged_but_a_dds_failure_is_not_hidden(
        domain_id: int, caplog: pytest.LogCaptureFixture) -> None:
    from cyclonedds.core import DDSException

    from homebot.transport.node import Node, loopback

    subscription = Node(loopback(domain_id)).subscription("/probe", "std_msgs/msg/String")
    reader = subscription.reader
    subscription.reader = _UnreadableReader(  # type: ignore[assignment]
        UnicodeDecodeError("utf-8", b"\xff", 0, 1, "invalid start byte"))
    assert subscription.take() == []
    assert "rt/probe: dropped unreadable samples (UnicodeDecodeError" in caplog.text
    subscription.reader = _UnreadableReader(DDSException(-3))  # type: ignore[assignment]
    with pytest.raises(DDSException):
        subscription.take()
    subscription.reader = reader
    assert subscription.take() == []


def test_a_client_that_reads_no_replies_is_waited_for_once_and_slows_no_one(
        domain_id: int, caplog: pytest.LogCaptureFixture) -> None:
    import time

    from homebot.transport.naming import SERVICE_QOS, request_topic
    from homebot.transport.node import Node, Publisher, loopback

    node = Node(loopback(domain_id))
    server = node.service("/homebot/parse", "homebot_msgs/srv/Parse",
                          lambda request: {"understood": True, "steps": request.command},
                          lambda reason: {"error": reason})
    server.route.timeout = 1.0
    deaf_node = Node(loopback(domain_id), node.types)  # a request writer, no reply reader
    deaf = Publisher(deaf_node, request_topic("/homebot/parse"),
                     node.types.request_struct("homebot_msgs/srv/Parse"), SERVICE_QOS)
    assert deaf.wait_for_subscribers(1, 10.0)
    for sequence in (1, 2, 3):
        deaf.publish(deaf.writer.topic.data_type(client_guid=7, sequence=sequence,
                                                 command="hello"))
    began = time.monotonic()
    answered = 0
    while answered < 3 and time.monotonic() - began < 10.0:
        answered += server.poll(0.5)
    assert answered == 3 and time.monotonic() - began < 2.5  # one wait of 1 s, not three
    assert caplog.text.count("reads no replies") == 1
    client = Node(loopback(domain_id), node.types).client("/homebot/parse",
                                                          "homebot_msgs/srv/Parse")
    assert client.wait_for_server(10.0)
    sequence = client.send(command="bring me a cola")
    assert server.poll(5.0) == 1
    assert client.receive(sequence, 5.0).steps == "bring me a cola"
