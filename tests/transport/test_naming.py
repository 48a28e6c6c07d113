"""ROS 2's names on the DDS wire and its QoS profiles."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("cyclonedds")

from cyclonedds.core import Policy

from homebot.transport.naming import (
    MAP_QOS,
    SENSOR_QOS,
    action_service,
    action_topic,
    check_frame,
    check_name,
    reply_topic,
    request_topic,
    topic,
)


def test_topics_services_and_actions_are_named_as_ros2_names_them() -> None:
    assert topic("/scan") == "rt/scan"
    assert topic("robot1/odom") == "rt/robot1/odom"
    assert request_topic("/homebot/parse") == "rq/homebot/parseRequest"
    assert reply_topic("/homebot/parse") == "rr/homebot/parseReply"
    goal = action_service("/navigate_to_pose", "send_goal")
    assert request_topic(goal) == "rq/navigate_to_pose/_action/send_goalRequest"
    assert reply_topic(action_service("navigate_to_pose", "get_result")) == \
        "rr/navigate_to_pose/_action/get_resultReply"
    assert request_topic(action_service("/navigate_to_pose", "cancel_goal")) == \
        "rq/navigate_to_pose/_action/cancel_goalRequest"
    assert topic(action_topic("/navigate_to_pose", "feedback")) == \
        "rt/navigate_to_pose/_action/feedback"
    assert topic(action_topic("/navigate_to_pose", "status")) == \
        "rt/navigate_to_pose/_action/status"
    with pytest.raises(ValueError):
        action_service("/navigate_to_pose", "result")
    with pytest.raises(ValueError):
        topic("/")


def test_the_map_is_transient_local_and_sensors_best_effort() -> None:
    qos = MAP_QOS.to_dds()
    assert qos[Policy.Durability] == Policy.Durability.TransientLocal
    assert qos[Policy.History] == Policy.History.KeepLast(1)
    assert SENSOR_QOS.to_dds()[Policy.Reliability] == Policy.Reliability.BestEffort


@pytest.mark.parametrize(("name", "rule"), [
    ("/tts\x01", "not letters, digits"), ("", "empty"), ("/", "empty"), ("/a//b", "'//'"),
    ("/a/", "ends in '/'"), ("/robot/1scan", "starting with a digit"), ("/a__b", "'__'"),
    ("/" + "a" * 300, "keep it to 247"), ("~/scan", "not letters"), ("/{ns}/scan", "not "),
    (5, "is text, not int"),
])
def test_a_name_that_breaks_ros2s_rules_is_refused_with_the_rule(name: object,
                                                                  rule: str) -> None:
    with pytest.raises(ValueError, match=re.escape(rule)):
        check_name(name)
    with pytest.raises(ValueError, match=re.escape(rule)):
        topic(name)  # type: ignore[arg-type]


def test_good_names_and_frames_pass() -> None:
    for name in ("/scan", "robot1/odom", "/navigate_to_pose/_action/send_goal", "/_hidden"):
        assert check_name(name) == name
    assert check_frame("base_link") == "base_link"
    with pytest.raises(ValueError, match="starts with '/'"):
        check_frame("/map")
