"""The Robot port's calls as JSON, for ``homebot_msgs/srv/RobotCall``.

Each method's arguments and result go as a JSON object; port types (``Pose``,
``Detection``, ``PersonPercept``, ``MoveReport``) as objects of their fields. ``serve``
runs one call on a robot, ``decode_result`` rebuilds the result on the caller's side.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable
from typing import Any

from homebot.errors import CallError
from homebot.geometry import Pose
from homebot.robot import Blocker, Detection, HelpRequest, MoveReport, PersonPercept, Robot

__all__ = ["CALLS", "decode_result", "encode", "serve"]


def encode(value: Any) -> Any:
    """A JSON-ready form of a port value."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {field.name: encode(getattr(value, field.name))
                for field in dataclasses.fields(value)}
    if isinstance(value, dict):
        return {key: encode(item) for key, item in value.items()}
    if isinstance(value, (tuple, list, frozenset, set)):
        items = sorted(value) if isinstance(value, (frozenset, set)) else value
        return [encode(item) for item in items]
    return value


def _pose(data: Any) -> Pose:
    return Pose(float(data["x"]), float(data["y"]), float(data["theta"]))


def _detection(data: Any) -> Detection:
    return Detection(data["label"], data["category"], int(data["handle"]))


def _person(data: Any) -> PersonPercept:
    return PersonPercept(data["name"], data["posture"], data["gesture"], tuple(data["clothes"]),
                         (float(data["position"][0]), float(data["position"][1])), data["room"])


def move_report(data: Any) -> MoveReport:
    return MoveReport(bool(data["reached"]), _pose(data["pose"]), float(data["distance"]),
                      Blocker(data["blocker"]) if data["blocker"] else None, data["door"],
                      data["person"], tuple(data["doors_passed"]))


def _same(data: Any) -> Any:
    return data


#: method -> (call it on a robot with JSON arguments, rebuild its result from JSON)
CALLS: dict[str, tuple[Callable[[Robot, dict[str, Any]], Any], Callable[[Any], Any]]] = {
    "hands": (lambda robot, a: list(robot.hands), tuple),
    "now": (lambda robot, a: robot.now(), float),
    "pose": (lambda robot, a: robot.pose(), _pose),
    "move_to": (lambda robot, a: robot.move_to(_pose(a["goal"]), frozenset(a["avoid_doors"]),
                                               a["escort"]), move_report),
    "perceive_objects": (lambda robot, a: robot.perceive_objects(a["placement"]),
                         lambda d: [_detection(item) for item in d]),
    "perceive_people": (lambda robot, a: robot.perceive_people(),
                        lambda d: [_person(item) for item in d]),
    "grasp": (lambda robot, a: robot.grasp(_detection(a["detection"]), a["hand"]), _same),
    "held": (lambda robot, a: robot.held(a["hand"]),
             lambda d: None if d is None else _detection(d)),
    "release": (lambda robot, a: robot.release(a["hand"], a["placement"]), _same),
    "hand_over": (lambda robot, a: robot.hand_over(a["hand"], a["person"]), bool),
    "open_door": (lambda robot, a: robot.open_door(a["door"]), bool),
    "door_is_open": (lambda robot, a: robot.door_is_open(a["door"]), _same),
    "say": (lambda robot, a: robot.say(a["text"]), _same),
    "ask": (lambda robot, a: robot.ask(a["person"], a["question"]), _same),
    "request": (lambda robot, a: robot.request(a["person"], HelpRequest(a["request"]),
                                               a["target"]), bool),
    "follow": (lambda robot, a: robot.follow(a["person"], None if a["goal"] is None
                                             else _pose(a["goal"])), move_report),
}


def serve(robot: Robot, method: str, arguments: str) -> str:
    """Run ``method`` on ``robot`` with JSON ``arguments``; the JSON result."""
    entry = CALLS.get(method)
    if entry is None:
        raise CallError(f"RobotCall: no method {method!r}; methods: {', '.join(CALLS)}")
    try:
        result = entry[0](robot, json.loads(arguments or "{}"))
    except (KeyError, ValueError, TypeError) as error:
        raise CallError(f"RobotCall {method}: malformed arguments {arguments!r} ({error})") \
            from None
    return json.dumps(encode(result))


def decode_result(method: str, result: str) -> Any:
    """The result of ``method`` from its JSON."""
    return CALLS[method][1](json.loads(result))
