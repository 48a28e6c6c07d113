"""ROS 2 actions over DDS: goal, feedback, result and cancel, as rcl_action lays them out.

An action ``/navigate_to_pose`` of type ``nav2_msgs/action/NavigateToPose`` is the services
``_action/send_goal``, ``_action/get_result`` and ``_action/cancel_goal`` and the topics
``_action/feedback`` and ``_action/status``. The server here is single-threaded: ``poll``
takes a new goal, runs ``execute`` to the end (which may publish feedback and ask whether a
cancel came), then answers ``get_result``. The client sends a goal, then waits for the
result while handing feedback to a callback, and notices when the server goes away.

No goal stops the server: one that ``execute`` raises on ends ABORTED with the result
``refuse(reason)`` builds, and is logged. A ``get_result`` for a goal the server never had
is answered at once with status UNKNOWN (as rclcpp does), and the server keeps the results
of its last ``KEPT_RESULTS`` goals only, so requests for made-up goals cost nothing lasting.
"""

from __future__ import annotations

import time
import uuid
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any

from homebot.transport.messages import stamp
from homebot.transport.naming import (
    ACTION_STATUS_QOS,
    DEFAULT_QOS,
    SERVICE_QOS,
    action_service,
    action_topic,
    reply_topic,
    request_topic,
)
from homebot.transport.node import (
    Node,
    Publisher,
    ReplyRoute,
    ServiceClient,
    Subscription,
    TransportError,
    refusal,
)

__all__ = ["KEPT_RESULTS", "ActionClient", "ActionServer", "GoalContext", "GoalStatus"]

#: Finished goals whose results a server keeps for ``get_result`` (rclcpp keeps them 15
#: minutes; a count keeps memory bounded whatever the rate of goals).
KEPT_RESULTS = 1000


class GoalStatus(IntEnum):
    """``action_msgs/msg/GoalStatus`` codes."""

    UNKNOWN = 0
    ACCEPTED = 1
    EXECUTING = 2
    CANCELING = 3
    SUCCEEDED = 4
    CANCELED = 5
    ABORTED = 6


@dataclass
class GoalContext:
    """What ``execute`` may do while a goal runs: feedback, and ask about a cancel."""

    server: ActionServer
    goal_id: bytes
    canceled: bool = False

    def publish_feedback(self, **fields: Any) -> None:
        self.server.publish_feedback(self.goal_id, **fields)

    def cancel_requested(self) -> bool:
        """Answer pending cancel requests; whether this goal is to be cancelled."""
        self.server.poll_cancel(self)
        return self.canceled


@dataclass
class _Finished:
    status: GoalStatus
    result: dict[str, Any] = field(default_factory=dict)


class ActionServer:
    """Serves one action; ``execute(goal, context) -> (status, result fields)``."""

    def __init__(self, node: Node, name: str, action: str,
                 execute: Callable[[Any, GoalContext], tuple[GoalStatus, dict[str, Any]]],
                 clock: Callable[[], float] = time.time,
                 refuse: Callable[[str], dict[str, Any]] = lambda reason: {}) -> None:
        """``clock`` stamps goal acceptance and status (a simulator passes its own);
        ``refuse(reason)`` is the result of a goal ``execute`` raised on (default: empty,
        for an action whose result has no field to say why)."""
        self.node, self.name, self.action, self.execute = node, name, action, execute
        self.clock, self.refuse = clock, refuse
        self.refused = 0  #: goals ended ABORTED because ``execute`` raised
        types = node.types
        self._channels: dict[str, tuple[Subscription[Any], Publisher[Any], type[Any]]] = {}
        self._routes: dict[str, ReplyRoute] = {}
        for part in ("send_goal", "get_result", "cancel_goal"):
            service = self._service_type(part)
            reply = types.reply_struct(service)
            requests = Subscription(node, request_topic(action_service(name, part)),
                                    types.request_struct(service), SERVICE_QOS)
            replies = Publisher(node, reply_topic(action_service(name, part)), reply,
                                SERVICE_QOS)
            self._channels[part] = (requests, replies, reply)
            self._routes[part] = ReplyRoute(requests, replies)
        self.feedback = node.publisher(action_topic(name, "feedback"),
                                       f"{action}_FeedbackMessage", DEFAULT_QOS)
        self.status = node.publisher(action_topic(name, "status"),
                                     "action_msgs/msg/GoalStatusArray", ACTION_STATUS_QOS)
        self._finished: OrderedDict[bytes, _Finished] = OrderedDict()

    def request_subscriptions(self) -> list[Subscription[Any]]:
        """The readers of the action's goal, result and cancel requests."""
        return [requests for requests, _replies, _struct in self._channels.values()]

    def _service_type(self, part: str) -> str:
        if part == "cancel_goal":
            return "action_msgs/srv/CancelGoal"
        return f"{self.action}_{'SendGoal' if part == 'send_goal' else 'GetResult'}"

    def _reply(self, part: str, request: Any, **fields: Any) -> None:
        _requests, replies, struct = self._channels[part]
        self._routes[part].ready(request)
        replies.publish(struct(client_guid=request.client_guid, sequence=request.sequence,
                               **fields))

    def publish_feedback(self, goal_id: bytes, **fields: Any) -> None:
        types = self.node.types
        self.feedback.publish(types.new(
            f"{self.action}_FeedbackMessage",
            goal_id=types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id),
            feedback=types.new(f"{self.action}_Feedback", **fields)))

    def _publish_status(self, goal_id: bytes, status: GoalStatus) -> None:
        types = self.node.types
        info = types.new("action_msgs/msg/GoalInfo",
                         goal_id=types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id),
                         stamp=stamp(types, self.clock()))
        self.status.publish(types.new("action_msgs/msg/GoalStatusArray", status_list=[
            types.new("action_msgs/msg/GoalStatus", goal_info=info, status=int(status))]))

    def poll_cancel(self, context: GoalContext | None = None) -> None:
        """Answer cancel requests: accepted for the running goal, else unknown or terminated."""
        requests, _replies, _struct = self._channels["cancel_goal"]
        for request in requests.take():
            wanted = bytes(request.goal_info.goal_id.uuid)
            if context is not None and wanted in (context.goal_id, bytes(16)):
                context.canceled = True
                self._publish_status(context.goal_id, GoalStatus.CANCELING)
                self._reply("cancel_goal", request, return_code=0,
                            goals_canceling=[request.goal_info])
            else:
                self._reply("cancel_goal", request,
                            return_code=3 if wanted in self._finished else 2)

    def poll(self, timeout: float = 0.0) -> int:
        """Take new goals (waiting up to ``timeout`` s), run each to its end; how many ran."""
        self.poll_cancel()
        send_goal = self._channels["send_goal"][0]
        goals = send_goal.wait(timeout) if timeout else send_goal.take()
        for request in goals:
            goal_id = bytes(request.goal_id.uuid)
            self._reply("send_goal", request, accepted=True,
                        stamp=stamp(self.node.types, self.clock()))
            self._publish_status(goal_id, GoalStatus.EXECUTING)
            context = GoalContext(self, goal_id)
            try:
                status, result = self.execute(request.goal, context)
            except Exception as error:  # no goal may stop the server
                self.refused += 1
                status, result = GoalStatus.ABORTED, self.refuse(refusal(self.name, error))
            self._finished[goal_id] = _Finished(status, result)
            while len(self._finished) > KEPT_RESULTS:
                self._finished.popitem(last=False)
            self._publish_status(goal_id, status)
        self._answer_results()
        return len(goals)

    def _answer_results(self) -> None:
        # Goals run to their end inside ``poll``, so a goal asked about is finished, or was
        # never had (or its result is long gone): that is answered UNKNOWN, as rclcpp does.
        for request in self._channels["get_result"][0].take():
            finished = self._finished.get(bytes(request.goal_id.uuid),
                                          _Finished(GoalStatus.UNKNOWN))
            result = self.node.types.new(f"{self.action}_Result", **finished.result)
            self._reply("get_result", request, status=int(finished.status), result=result)


class ActionClient:
    """Sends goals to one action server and waits for results, with feedback and cancel."""

    def __init__(self, node: Node, name: str, action: str) -> None:
        self.node, self.name, self.action = node, name, action
        self.send_goal = ServiceClient(node, action_service(name, "send_goal"),
                                       f"{action}_SendGoal")
        self.get_result = ServiceClient(node, action_service(name, "get_result"),
                                        f"{action}_GetResult")
        self.cancel_goal = ServiceClient(node, action_service(name, "cancel_goal"),
                                         "action_msgs/srv/CancelGoal")
        self.feedback = node.subscription(action_topic(name, "feedback"),
                                          f"{action}_FeedbackMessage", DEFAULT_QOS)
        self.status = node.subscription(action_topic(name, "status"),
                                        "action_msgs/msg/GoalStatusArray", ACTION_STATUS_QOS)

    def ready(self) -> bool:
        return self.send_goal.ready() and self.get_result.ready()

    def wait_for_server(self, timeout: float) -> bool:
        return all(client.wait_for_server(timeout)
                   for client in (self.send_goal, self.get_result, self.cancel_goal))

    def send(self, timeout: float = 5.0, **goal: Any) -> bytes | None:
        """Send a goal; its id when accepted, None when rejected."""
        types = self.node.types
        goal_id = uuid.uuid4().bytes
        reply = self.send_goal.call(
            timeout, goal_id=types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id),
            goal=types.new(f"{self.action}_Goal", **goal))
        return goal_id if reply.accepted else None

    def result(self, goal_id: bytes, timeout: float,
               on_feedback: Callable[[Any], None] | None = None) -> tuple[GoalStatus, Any]:
        """Wait for a goal's result, giving its feedback to ``on_feedback`` meanwhile.

        Raises ``TransportError`` when the server goes away or ``timeout`` s pass.
        """
        types = self.node.types
        sequence = self.get_result.send(
            goal_id=types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id))
        deadline = time.monotonic() + timeout

        def alive() -> bool:
            for message in self.feedback.take():
                if on_feedback is not None and bytes(message.goal_id.uuid) == goal_id:
                    on_feedback(message.feedback)
            return time.monotonic() < deadline

        try:
            reply = self.get_result.receive(sequence, timeout, alive)
        except TransportError:
            raise TransportError(f"action {self.name}: the server went away or gave no result "
                                 f"within {timeout:g} s") from None
        alive()  # feedback that came with the result
        return GoalStatus(reply.status), reply.result

    def cancel(self, goal_id: bytes, timeout: float = 2.0) -> bool:
        """Ask the server to cancel a goal; whether it accepted."""
        types = self.node.types
        info = types.new("action_msgs/msg/GoalInfo",
                         goal_id=types.new("unique_identifier_msgs/msg/UUID", uuid=goal_id))
        reply = self.cancel_goal.call(timeout, goal_info=info)
        return int(reply.return_code) == 0
