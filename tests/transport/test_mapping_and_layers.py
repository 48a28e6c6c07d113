"""The RosRobot mapping file, and the transport's place in the layers."""

from __future__ import annotations

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
