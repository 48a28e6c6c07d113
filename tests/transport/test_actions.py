"""A full NavigateToPose exchange: goal, feedback, result, status, and cancel."""

from __future__ import annotations

import threading
from typing import Any

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

from homebot.errors import TransportError
from homebot.geometry import Pose
from homebot.transport.actions import (
    ActionClient,
    ActionServer,
    GoalContext,
    GoalStatus,
)
from homebot.transport.messages import pose_of, pose_stamped, seconds
from homebot.transport.node import Node, loopback

NAVIGATE = "nav2_msgs/action/NavigateToPose"


def _serve(server: ActionServer, goals: int) -> threading.Thread:
    def run() -> None:
        served = 0
        for _ in range(200):  # at most 200 waits of 0.05 s: the test is bounded
            served += server.poll(0.05)
            if served >= goals:
                server.poll(0.05)  # answer the last get_result
                break
    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread


def test_navigate_to_pose_goal_feedback_and_result(domain_id: int) -> None:
    node = Node(loopback(domain_id))
    seen: list[Any] = []

    def execute(goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        seen.append(goal)
        target = pose_of(goal.pose.pose)
        for step in (0.25, 0.5, 1.0):
            at = Pose(target.x * step, target.y * step, target.theta)
            context.publish_feedback(current_pose=pose_stamped(node.types, at, step),
                                     distance_remaining=1.0 - step, number_of_recoveries=0)
        return GoalStatus.SUCCEEDED, {}

    server = ActionServer(node, "/navigate_to_pose", NAVIGATE, execute)
    client = ActionClient(Node(loopback(domain_id), node.types), "/navigate_to_pose", NAVIGATE)
    assert client.wait_for_server(10.0)
    thread = _serve(server, 1)
    goal = pose_stamped(node.types, Pose(2.0, -1.0, 0.5), 3.0)
    goal_id = client.send(5.0, pose=goal, behavior_tree="")
    assert goal_id is not None
    feedback: list[Any] = []
    status, result = client.result(goal_id, 10.0, feedback.append)
    thread.join(10.0)
    assert status is GoalStatus.SUCCEEDED
    assert pose_of(seen[0].pose.pose).x == 2.0 and seen[0].pose.header.frame_id == "map"
    assert seconds(seen[0].pose.header.stamp) == 3.0
    assert result.result is not None
    # Feedback comes in order on a reliable topic; the last one is at the goal.
    assert [round(item.distance_remaining, 2) for item in feedback] == [0.75, 0.5, 0.0]
    assert pose_of(feedback[-1].current_pose.pose).y == pytest.approx(-1.0)
    statuses = client.status.take()
    assert statuses and statuses[-1].status_list[0].status == GoalStatus.SUCCEEDED
    assert bytes(statuses[-1].status_list[0].goal_info.goal_id.uuid) == goal_id


def test_a_cancelled_goal_ends_cancelled(domain_id: int) -> None:
    node = Node(loopback(domain_id))
    client_node = Node(loopback(domain_id), node.types)
    client = ActionClient(client_node, "/navigate_to_pose", NAVIGATE)
    box: dict[str, Any] = {}

    def execute(goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        # The robot drives until it hears the cancel (bounded: at most 200 checks).
        for _ in range(200):
            context.publish_feedback(distance_remaining=1.0)
            if box.get("cancel_sent") is not None and context.cancel_requested():
                return GoalStatus.CANCELED, {}
            box["running"].set()
            box["cancel_sent"].wait(0.05)
        return GoalStatus.SUCCEEDED, {}

    box["running"], box["cancel_sent"] = threading.Event(), threading.Event()
    server = ActionServer(node, "/navigate_to_pose", NAVIGATE, execute)
    assert client.wait_for_server(10.0)
    thread = _serve(server, 1)
    goal_id = client.send(5.0, pose=pose_stamped(node.types, Pose(1.0, 1.0), 0.0))
    assert goal_id is not None
    assert box["running"].wait(10.0)
    sequence = client.cancel_goal.send(goal_info=node.types.new(
        "action_msgs/msg/GoalInfo",
        goal_id=node.types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id)))
    box["cancel_sent"].set()
    assert client.cancel_goal.receive(sequence, 10.0).return_code == 0
    status, _ = client.result(goal_id, 10.0)
    thread.join(10.0)
    assert status is GoalStatus.CANCELED


def test_a_goal_that_raises_ends_aborted_with_its_reason_and_the_server_goes_on(
        domain_id: int) -> None:
    node = Node(loopback(domain_id))

    def execute(goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        if goal.command == "":
            raise TransportError("the command is empty")
        if goal.command == "bug":
            raise ZeroDivisionError("a fault of the server")
        return GoalStatus.SUCCEEDED, {"success": True, "speech": goal.command}

    server = ActionServer(node, "/command", "homebot_msgs/action/Command", execute,
                          refuse=lambda reason: {"success": False, "reason": reason})
    client = ActionClient(Node(loopback(domain_id), node.types), "/command",
                          "homebot_msgs/action/Command")
    assert client.wait_for_server(10.0)
    thread = _serve(server, 3)
    outcomes = []
    for command in ("", "bug", "hello"):
        goal_id = client.send(5.0, command=command)
        assert goal_id is not None
        outcomes.append(client.result(goal_id, 10.0))
    thread.join(10.0)
    (empty, empty_result), (bug, bug_result), (hello, hello_result) = outcomes
    assert empty is GoalStatus.ABORTED and empty_result.reason == "the command is empty"
    assert bug is GoalStatus.ABORTED and "internal error" in bug_result.reason
    assert hello is GoalStatus.SUCCEEDED and hello_result.speech == "hello"
    assert server.refused == 2


def test_results_of_goals_never_had_are_unknown_and_old_results_are_let_go(
        domain_id: int, monkeypatch: pytest.MonkeyPatch) -> None:
    import homebot.transport.actions as actions

    monkeypatch.setattr(actions, "KEPT_RESULTS", 2)
    node = Node(loopback(domain_id))
    server = ActionServer(node, "/navigate_to_pose", NAVIGATE,
                          lambda goal, context: (GoalStatus.SUCCEEDED, {}))
    client = ActionClient(Node(loopback(domain_id), node.types), "/navigate_to_pose", NAVIGATE)
    assert client.wait_for_server(10.0)
    stop = threading.Event()

    def serve() -> None:
        for _ in range(400):  # bounded: at most 400 waits of 0.05 s
            server.poll(0.05)
            if stop.is_set():
                return
    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    goals = [client.send(5.0) for _ in range(3)]
    assert None not in goals
    assert client.result(bytes(16), 10.0)[0] is GoalStatus.UNKNOWN
    assert client.result(goals[0] or b"", 10.0)[0] is GoalStatus.UNKNOWN  # let go
    assert client.result(goals[2] or b"", 10.0)[0] is GoalStatus.SUCCEEDED
    stop.set()
    thread.join(10.0)
