"""``RosRobot``: the Robot port over a team's own ROS 2 stack, named in a mapping file.

``navigate`` (``move_to``) becomes Nav2's ``NavigateToPose`` action, with feedback and
cancel; speech goes to a TTS topic (``std_msgs/msg/String``); the port's other methods go
to a ``homebot_msgs/srv/RobotCall`` service. The mapping file (YAML) names them::

    navigate_action: /navigate_to_pose   # nav2_msgs/action/NavigateToPose
    frame: map                           # the goal's frame
    speech_topic: /tts                   # std_msgs/msg/String; null: none
    robot_call: /homebot/robot           # homebot_msgs/srv/RobotCall; null: none
    timeout: 600                         # seconds a goal may take (wall clock)
    call_timeout: 10                     # seconds a call may take (wall clock)
    liveness: 2                          # seconds of silence after which the robot is lost

When the robot call service is there, its replies carry the robot's clock and its
events; they go into this robot's event log as they happened there. A server that goes
away raises ``RobotLost`` (within ``liveness`` seconds of wall time).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from homebot.cancel import CancelToken
from homebot.errors import RobotLost, TransportError
from homebot.events import EventLog
from homebot.geometry import Pose
from homebot.robot import Blocker, Detection, HelpRequest, MoveReport, PersonPercept, Robot
from homebot.transport.actions import ActionClient, GoalStatus
from homebot.transport.calls import decode_result, encode, move_report
from homebot.transport.messages import pose_of, pose_stamped
from homebot.transport.naming import check_frame, check_name
from homebot.transport.node import Node
from homebot.yamlfile import field_error, load_yaml_document

__all__ = ["RobotLost", "RobotMapping", "RosRobot"]


@dataclass(frozen=True, slots=True)
class RobotMapping:
    """Which ROS 2 names the Robot port's methods go to (see the module docstring)."""

    navigate_action: str = "/navigate_to_pose"
    frame: str = "map"
    speech_topic: str | None = "/homebot/speech"
    robot_call: str | None = "/homebot/robot"
    timeout: float = 600.0
    call_timeout: float = 10.0
    liveness: float = 2.0

    @classmethod
    def load(cls, path: Path) -> RobotMapping:
        """Read a mapping file; an unknown key or a bad value names the file and the fix."""
        document = load_yaml_document(path, TransportError)
        data = document.data or {}
        if not isinstance(data, dict):
            raise TransportError(f"{path}: line 1: a ROS 2 mapping file is a YAML mapping of "
                                 "names")
        known = set(cls.__dataclass_fields__)
        unknown = sorted(set(data) - known)
        if unknown:
            raise TransportError(field_error(
                document, [unknown[0]], f"unknown key(s) {', '.join(unknown)}; "
                f"known: {', '.join(sorted(known))}"))
        for key in ("timeout", "call_timeout", "liveness"):
            value = data.get(key, 1.0)
            if not isinstance(value, (int, float)) or not 0 < value < math.inf:
                raise TransportError(field_error(document, [key],
                                                 "must be a positive number of seconds"))
        for key, check in (("navigate_action", check_name), ("speech_topic", check_name),
                           ("robot_call", check_name), ("frame", check_frame)):
            if key not in data or (data[key] is None and key in ("speech_topic", "robot_call")):
                continue  # left out: homebot's default; null: the robot offers none
            try:
                check(data[key])
            except ValueError as error:
                raise TransportError(field_error(document, [key], str(error))) from None
        return cls(**data)


class RosRobot(Robot):
    """A robot reached over ROS 2: Nav2 for motion, a robot call service for the rest."""

    def __init__(self, node: Node, mapping: RobotMapping | None = None,
                 events: EventLog | None = None) -> None:
        self.node = node
        self.mapping = mapping or RobotMapping()
        self._now = 0.0
        self.events = events or EventLog(self.now)
        self.navigation = ActionClient(node, self.mapping.navigate_action,
                                       "nav2_msgs/action/NavigateToPose")
        self.speech = (node.publisher(self.mapping.speech_topic, "std_msgs/msg/String")
                       if self.mapping.speech_topic else None)
        self.calls = (node.client(self.mapping.robot_call, "homebot_msgs/srv/RobotCall")
                      if self.mapping.robot_call else None)
        self._hands: tuple[str, ...] = ("right",)
        self.feedback: list[Pose] = []  #: poses the last goal's feedback reported

    def connect(self, timeout: float) -> None:
        """Wait for the robot's servers; learn its hands, clock and events so far."""
        if not self.navigation.wait_for_server(timeout) or (
                self.calls is not None and not self.calls.wait_for_server(timeout)):
            raise RobotLost(f"no robot answers on ROS 2 domain {self.node.settings.domain_id} "
                            f"within {timeout:g} s; start it (homebot sim serve) or check the "
                            "domain id, the network interface and the mapping file")
        if self.calls is not None:
            self._hands = tuple(self._call("hands"))

    def finish(self) -> None:
        """Ask the robot to log where the run left things (a simulator logs its truth)."""
        if self.calls is not None:
            self._call("final_state")

    # ------------------------------------------------------------ plumbing

    def _call(self, method: str, **arguments: Any) -> Any:
        if self.calls is None:
            raise TransportError(f"the ROS 2 mapping names no robot_call service, so "
                               f"'{method}' cannot reach the robot; name one in the mapping")
        sequence = self.calls.send(method=method, arguments=json.dumps(encode(arguments)))
        try:
            reply = self.calls.receive(sequence, self.mapping.call_timeout)
        except TransportError as error:
            raise RobotLost(f"lost the robot during '{method}': {error}") from None
        self._replay(reply.events)
        self._now = float(reply.now)
        result = json.loads(reply.result)
        if isinstance(result, dict) and set(result) == {"error"}:
            raise TransportError(str(result["error"]))
        if method == "last_move":
            return move_report(result)
        return decode_result(method, reply.result) if method in _DECODED else result

    def _replay(self, events: str) -> None:
        """Record the robot's events here, each at the time it happened there."""
        for time, kind, data in json.loads(events or "[]"):
            self._now = float(time)
            self.events.record(kind, **data)

    # ------------------------------------------------------------ the port

    @property
    def hands(self) -> tuple[str, ...]:
        return self._hands

    def now(self) -> float:
        return self._now

    def pose(self) -> Pose:
        result: Pose = self._call("pose")
        return result

    def move_to(self, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *,
                cancel: CancelToken | None = None) -> MoveReport:
        # ``cancel`` is checked before the goal is sent; a goal under way runs to its end.
        if cancel is not None and cancel.cancelled:
            return MoveReport(False, self.pose(), 0.0, Blocker.CANCELLED)
        if self.calls is not None:
            self._call("move_options", avoid_doors=sorted(avoid_doors), escort=escort)
        self.feedback = []
        try:
            goal_id = self.navigation.send(
                self.mapping.call_timeout,
                pose=pose_stamped(self.node.types, goal, self._now, self.mapping.frame))
            if goal_id is None:
                return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
            status, _result = self.navigation.result(
                goal_id, self.mapping.timeout,
                lambda feedback: self.feedback.append(pose_of(feedback.current_pose.pose)))
        except TransportError as error:
            raise RobotLost(f"lost the robot while navigating: {error}") from None
        if self.calls is not None:
            report: MoveReport = self._call("last_move")
            return report
        pose = self.feedback[-1] if self.feedback else goal
        reached = status is GoalStatus.SUCCEEDED
        return MoveReport(reached, pose, 0.0, None if reached else Blocker.NO_PATH)

    def perceive_objects(self, placement: str) -> list[Detection]:
        result: list[Detection] = self._call("perceive_objects", placement=placement)
        return result

    def perceive_people(self) -> list[PersonPercept]:
        result: list[PersonPercept] = self._call("perceive_people")
        return result

    def grasp(self, detection: Detection, hand: str) -> None:
        self._call("grasp", detection=detection, hand=hand)

    def held(self, hand: str) -> Detection | None:
        result: Detection | None = self._call("held", hand=hand)
        return result

    def release(self, hand: str, placement: str) -> None:
        self._call("release", hand=hand, placement=placement)

    def hand_over(self, hand: str, person: str) -> bool:
        return bool(self._call("hand_over", hand=hand, person=person))

    def open_door(self, door: str) -> bool:
        return bool(self._call("open_door", door=door))

    def door_is_open(self, door: str) -> bool | None:
        result: bool | None = self._call("door_is_open", door=door)
        return result

    def say(self, text: str) -> None:
        if self.speech is not None:
            self.speech.publish(self.node.types.new("std_msgs/msg/String", data=text))
        if self.calls is not None:
            self._call("say", text=text)

    def ask(self, person: str, question: str) -> str | None:
        result: str | None = self._call("ask", person=person, question=question)
        return result

    def request(self, person: str, request: HelpRequest, target: str) -> bool:
        return bool(self._call("request", person=person, request=str(request), target=target))

    def follow(self, person: str, goal: Pose | None, *,
               cancel: CancelToken | None = None) -> MoveReport:
        if cancel is not None and cancel.cancelled:
            return MoveReport(False, self.pose(), 0.0, Blocker.CANCELLED)
        result: MoveReport = self._call("follow", person=person, goal=goal)
        return result


_DECODED = {"pose", "perceive_objects", "perceive_people", "held", "follow"}
