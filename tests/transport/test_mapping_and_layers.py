"""The RosRobot mapping file, and the transport's place in the layers."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from homebot.errors import HomebotError

SOURCE = Path(__file__).resolve().parents[2] / "src" / "homebot"


def test_the_transport_never_reaches_into_the_simulator() -> None:
    for path in (SOURCE / "transport").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "homebot.sim" not in text.replace("homebot.sim serve", ""), path.name


def test_a_mapping_file_names_the_robots_interfaces(tmp_path: Path) -> None:
    pytest.importorskip("cyclonedds")
    from homebot.transport.ros_robot import RobotMapping

    path = tmp_path / "mapping.yaml"
    path.write_text("navigate_action: /robot1/navigate_to_pose\nspeech_topic: /tts\n"
                    "robot_call: null\nliveness: 3\n", encoding="utf-8")
    mapping = RobotMapping.load(path)
    assert mapping.navigate_action == "/robot1/navigate_to_pose"
    assert mapping.robot_call is None and mapping.speech_topic == "/tts"
    path.write_text("navigate: /navigate_to_pose\n", encoding="utf-8")
    with pytest.raises(HomebotError, match=r"line 1: navigate: unknown key.*navigate.*known"):
        RobotMapping.load(path)
    path.write_text("timeout: -1\n", encoding="utf-8")
    with pytest.raises(HomebotError, match="line 1: timeout: must be a positive number"):
        RobotMapping.load(path)


@pytest.mark.parametrize(("text", "says"), [
    ('speech_topic: "/tts\\x01"\n', r"line 1: speech_topic: the ROS 2 name '/tts\\x01' is not"),
    ("robot_call: /robot//call\n", "line 1: robot_call: the ROS 2 name '/robot//call' ends"),
    ("timeout: 5\nnavigate_action: 7\n", "line 2: navigate_action: a ROS 2 name is text"),
    ("frame: /map\n", "line 1: frame: the frame id '/map' starts with '/'"),
])
def test_a_mapping_file_with_a_bad_ros2_name_says_file_line_and_rule(
        tmp_path: Path, text: str, says: str) -> None:
    pytest.importorskip("cyclonedds")
    from homebot.transport.ros_robot import RobotMapping

    path = tmp_path / "mapping.yaml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(HomebotError, match=f"{re.escape(str(path))}: {says}"):
        RobotMapping.load(path)
