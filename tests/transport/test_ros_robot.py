"""RosRobot on a team's stack that offers only Nav2 and a TTS topic (no RobotCall)."""

from __future__ import annotations

import threading
from typing import Any

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

from homebot.errors import TransportError
from homebot.geometry import Pose
from homebot.robot import Blocker
from homebot.transport.actions import ActionServer, GoalContext, GoalStatus
from homebot.transport.messages import pose_of, pose_stamped
from homebot.transport.node import Node, loopback
from homebot.transport.ros_robot import RobotMapping, RosRobot


def test_navigation_goes_to_nav2_and_speech_to_the_tts_topic(domain_id: int) -> None:
    nav2 = Node(loopback(domain_id))

    def navigate(goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        target = pose_of(goal.pose.pose)
        if target.x > 50:  # off the map: Nav2 aborts
            return GoalStatus.ABORTED, {}
        context.publish_feedback(current_pose=pose_stamped(nav2.types, target, 1.0),
                                 distance_remaining=0.0)
        return GoalStatus.SUCCEEDED, {}

    server = ActionServer(nav2, "/robot1/navigate_to_pose", "nav2_msgs/action/NavigateToPose",
                          navigate)
    tts = nav2.subscription("/tts", "std_msgs/msg/String")
    stop = threading.Event()

    def serve() -> None:
        for _ in range(600):  # at most 30 s
            server.poll(0.05)
            if stop.is_set():
                break

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        mapping = RobotMapping(navigate_action="/robot1/navigate_to_pose", speech_topic="/tts",
                               robot_call=None)
        robot = RosRobot(Node(loopback(domain_id), nav2.types), mapping)
        robot.connect(10.0)
        report = robot.move_to(Pose(1.5, -2.0, 0.3))
        assert report.reached and report.pose.x == pytest.approx(1.5)
        assert report.pose.theta == pytest.approx(0.3)
        assert robot.feedback and robot.feedback[-1].y == pytest.approx(-2.0)
        failed = robot.move_to(Pose(99.0, 0.0))
        assert not failed.reached and failed.blocker is Blocker.NO_PATH
        assert tts.wait_for_publishers(1, 10.0)
        robot.say("I am on my way")
        assert [message.data for message in tts.wait(10.0)] == ["I am on my way"]
        with pytest.raises(TransportError, match="names no robot_call service"):
            robot.perceive_people()
    finally:
        stop.set()
        thread.join(10.0)
