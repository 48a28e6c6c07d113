"""The Robot port's calls as JSON, for ``homebot_msgs/srv/RobotCall``.

Each method's arguments and result go as a JSON object; port types (``Pose``,
``Detection``, ``PersonPercept``, ``MoveReport``) as objects of their fields. ``serve``
runs one call on a robot, ``decode_result`` rebuilds the result on the caller's side.

Every method's arguments have a schema (pydantic, strict, no unknown fields, names and
texts and lists of bounded length, finite numbers); ``parse_arguments`` refuses a text over
``MAX_ARGUMENTS`` before parsing it, and parses with a depth limit (pydantic's JSON parser
stops at 200 levels), so no request can reach the robot malformed or exhaust the server.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, StringConstraints, ValidationError

from homebot.errors import CallError
from homebot.geometry import Pose
from homebot.robot import Blocker, Detection, HelpRequest, MoveReport, PersonPercept, Robot

__all__ = ["CALLS", "MAX_ARGUMENTS", "Arguments", "Call", "MoveOptions", "decode_result",
           "encode", "parse_arguments", "serve"]


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


# ------------------------------------------------------------ the arguments' schema

#: Bytes of a call's JSON arguments; anything longer is refused before it is parsed.
MAX_ARGUMENTS = 16 * 1024
#: Characters of a name (a place, a door, a person, a hand) and of a text said or asked.
MAX_NAME, MAX_TEXT = 200, 2000
#: Items of a list argument (the doors to avoid).
MAX_ITEMS = 100

Name = Annotated[str, StringConstraints(max_length=MAX_NAME)]
Text = Annotated[str, StringConstraints(max_length=MAX_TEXT)]
Number = Annotated[float, Field(allow_inf_nan=False)]


class Arguments(BaseModel):
    """A call's arguments: exactly these fields, of these types (strict: no coercion)."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True)


class PoseArgument(Arguments):
    x: Number
    y: Number
    theta: Number

    def pose(self) -> Pose:
        return Pose(self.x, self.y, self.theta)


class DetectionArgument(Arguments):
    label: Name
    category: Name
    handle: int
    position: tuple[Number, Number] | None = None
    size: Number | None = None
    mass: Number | None = None
    heading: Number | None = None

    def detection(self) -> Detection:
        return Detection(self.label, self.category, self.handle)


class NoArguments(Arguments):
    pass


class MoveToArguments(Arguments):
    goal: PoseArgument
    avoid_doors: Annotated[list[Name], Field(max_length=MAX_ITEMS)] = []
    escort: Name | None = None


class MoveOptions(Arguments):
    """``move_options`` (``homebot sim serve``): the doors to avoid, the person to escort."""

    avoid_doors: Annotated[list[Name], Field(max_length=MAX_ITEMS)] = []
    escort: Name | None = None


class PlacementArguments(Arguments):
    placement: Name


class GraspArguments(Arguments):
    detection: DetectionArgument
    hand: Name


class HandArguments(Arguments):
    hand: Name


class ReleaseArguments(Arguments):
    hand: Name
    placement: Name


class HandOverArguments(Arguments):
    hand: Name
    person: Name


class DoorArguments(Arguments):
    door: Name


class SayArguments(Arguments):
    text: Text


class AskArguments(Arguments):
    person: Name
    question: Text


class RequestArguments(Arguments):
    person: Name
    request: HelpRequest = Field(strict=False)  # its value as text: "open_door"
    target: Name


class FollowArguments(Arguments):
    person: Name
    goal: PoseArgument | None = None


@dataclass(frozen=True, slots=True)
class Call:
    """One method of the port: its arguments' schema, how to run it, how to read its result."""

    arguments: type[Arguments]
    run: Callable[[Robot, Any], Any]
    decode: Callable[[Any], Any]


CALLS: dict[str, Call] = {
    "hands": Call(NoArguments, lambda robot, a: list(robot.hands), tuple),
    "now": Call(NoArguments, lambda robot, a: robot.now(), float),
    "pose": Call(NoArguments, lambda robot, a: robot.pose(), _pose),
    "move_to": Call(MoveToArguments, lambda robot, a: robot.move_to(
        a.goal.pose(), frozenset(a.avoid_doors), a.escort), move_report),
    "perceive_objects": Call(PlacementArguments,
                             lambda robot, a: robot.perceive_objects(a.placement),
                             lambda d: [_detection(item) for item in d]),
    "perceive_people": Call(NoArguments, lambda robot, a: robot.perceive_people(),
                            lambda d: [_person(item) for item in d]),
    "grasp": Call(GraspArguments, lambda robot, a: robot.grasp(a.detection.detection(), a.hand),
                  _same),
    "held": Call(HandArguments, lambda robot, a: robot.held(a.hand),
                 lambda d: None if d is None else _detection(d)),
    "release": Call(ReleaseArguments, lambda robot, a: robot.release(a.hand, a.placement),
                    _same),
    "hand_over": Call(HandOverArguments, lambda robot, a: robot.hand_over(a.hand, a.person),
                      bool),
    "open_door": Call(DoorArguments, lambda robot, a: robot.open_door(a.door), bool),
    "door_is_open": Call(DoorArguments, lambda robot, a: robot.door_is_open(a.door), _same),
    "say": Call(SayArguments, lambda robot, a: robot.say(a.text), _same),
    "ask": Call(AskArguments, lambda robot, a: robot.ask(a.person, a.question), _same),
    "request": Call(RequestArguments,
                    lambda robot, a: robot.request(a.person, a.request, a.target), bool),
    "follow": Call(FollowArguments, lambda robot, a: robot.follow(
        a.person, None if a.goal is None else a.goal.pose()), move_report),
}


def parse_arguments(method: str, arguments: str, schema: type[Arguments]) -> Any:
    """The arguments of ``method`` checked against ``schema``; ``CallError`` says what is
    wrong. The size is checked first and the JSON parser has a depth limit, so neither a
    huge nor a deeply nested text costs more than a glance."""
    if len(arguments) > MAX_ARGUMENTS:
        raise CallError(f"RobotCall {method}: arguments of {len(arguments)} characters; "
                        f"at most {MAX_ARGUMENTS}")
    try:
        return schema.model_validate_json(arguments or "{}")
    except ValidationError as error:
        raise CallError(f"RobotCall {method}: malformed arguments: {_first_problem(error)}") \
            from None


def _first_problem(error: ValidationError) -> str:
    """The first problem pydantic found, in one line (where, what), without the input."""
    problems = error.errors(include_url=False, include_input=False)
    where = ".".join(str(step) for step in problems[0]["loc"]) or "(arguments)"
    more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
    return f"{where}: {problems[0]['msg']}{more}"


def serve(robot: Robot, method: str, arguments: str) -> str:
    """Run ``method`` on ``robot`` with JSON ``arguments``; the JSON result."""
    call = CALLS.get(method)
    if call is None:
        raise CallError(f"RobotCall: no method {method[:60]!a}; "
                        f"methods: {', '.join(CALLS)}")
    return json.dumps(encode(call.run(robot, parse_arguments(method, arguments,
                                                             call.arguments))))


def decode_result(method: str, result: str) -> Any:
    """The result of ``method`` from its JSON."""
    return CALLS[method].decode(json.loads(result))
