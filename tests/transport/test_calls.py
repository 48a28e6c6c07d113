"""RobotCall arguments: a schema per method, checked before anything reaches the robot."""

from __future__ import annotations

import json

import pytest

from homebot.errors import CallError
from homebot.geometry import Pose
from homebot.robot import HelpRequest
from homebot.transport.calls import (
    CALLS,
    MAX_ARGUMENTS,
    MoveOptions,
    encode,
    parse_arguments,
)


def test_what_a_ros_robot_sends_is_what_the_schema_takes() -> None:
    arguments = json.dumps(encode({"goal": Pose(1, 2.5, 0.1), "avoid_doors": ["hall_door"],
                                   "escort": None}))
    move = parse_arguments("move_to", arguments, CALLS["move_to"].arguments)
    assert move.goal.pose() == Pose(1.0, 2.5, 0.1) and move.avoid_doors == ["hall_door"]
    request = parse_arguments("request", json.dumps(
        {"person": "anna", "request": str(HelpRequest.OPEN_DOOR), "target": "hall_door"}),
        CALLS["request"].arguments)
    assert request.request is HelpRequest.OPEN_DOOR
    assert parse_arguments("pose", "", CALLS["pose"].arguments) is not None


@pytest.mark.parametrize(("method", "arguments", "says"), [
    ("move_options", "[1]", r"move_options: malformed arguments: \(arguments\): Input should "
                            "be an object"),
    ("move_options", '{"avoid_doors": "hall"}', "avoid_doors: Input should be a valid"),
    ("say", "[" * 6000 + "]" * 6000, "recursion limit exceeded"),
    ("say", '{"text": "' + "x" * MAX_ARGUMENTS + '"}', f"at most {MAX_ARGUMENTS}"),
    ("move_to", '{"goal": {"x": NaN, "y": 0, "theta": 0}}', "goal.x: Input should be a finite"),
    ("move_to", '{"goal": {"x": "1", "y": 0, "theta": 0}}', "goal.x: Input should be a valid"),
    ("say", '{"text": "hi", "volume": 11}', "volume: Extra inputs are not permitted"),
    ("ask", '{"person": "anna"}', "question: Field required"),
    ("request", '{"person": "a", "request": "fly", "target": ""}', "request: Input should be"),
    ("open_door", '{"door": ' + json.dumps("d" * 201) + "}", "door: String should have at most"),
    ("say", '{"text": "hi"', "Invalid JSON"),
])
def test_a_malformed_call_is_refused_with_where_and_what(method: str, arguments: str,
                                                         says: str) -> None:
    schema = MoveOptions if method == "move_options" else CALLS[method].arguments
    with pytest.raises(CallError, match=says):
        parse_arguments(method, arguments, schema)
