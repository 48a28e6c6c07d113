"""homebot as a ROS 2 node: what ``homebot ros serve`` offers a team's stack.

- ``/homebot/command``: the action ``homebot_msgs/action/Command``. The goal is a command
  in words ("bring me a cola"); feedback names each step as it starts; the result says
  whether it succeeded, what the robot said, and why not.
- ``/homebot/events``: every event of the log as a JSON line (``std_msgs/msg/String``;
  reliable, keep all: subscribe with keep all, or a deep history, to miss none).
- ``/homebot/speech``: what the robot says (``std_msgs/msg/String``).
- ``/homebot/parse``: the service ``homebot_msgs/srv/Parse``: a command's skill steps as
  JSON, or why it was not understood.

The server is given two functions (``parse`` and ``carry_out``) and the event log; the
command line wires them to the language layer and the executive.

No request stops the server. A command that is empty, longer than the language layer's
``MAX_COMMAND_LENGTH`` characters or holds control characters (a line break too) is refused
before the language layer sees it: ``/homebot/parse`` answers ``understood: false`` with the
reason in ``error``, a ``/homebot/command`` goal ends ABORTED with the reason in ``reason``.
Any error while parsing or carrying out a command is answered the same way and logged.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from homebot.errors import TransportError
from homebot.events import Event, EventLog
from homebot.language.parser import MAX_COMMAND_LENGTH
from homebot.transport.actions import ActionServer, GoalContext, GoalStatus
from homebot.transport.naming import RELIABLE_ALL_QOS
from homebot.transport.node import Arrivals, Node, shown

__all__ = ["CommandOutcome", "CommandServer", "check_command"]


def check_command(text: str, where: str) -> str:
    """``text`` when it can be a command; else ``TransportError`` saying why."""
    if not text.strip():
        raise TransportError(f"{where}: the command is empty; say what the robot should do")
    if len(text) > MAX_COMMAND_LENGTH:
        raise TransportError(f"{where}: the command has {len(text)} characters; keep it "
                             f"under {MAX_COMMAND_LENGTH}, one task at a time")
    if not text.isprintable():
        raise TransportError(f"{where}: the command {shown(text)} holds control characters; "
                             "send plain text")
    return text


@dataclass(frozen=True, slots=True)
class CommandOutcome:
    """How a command ended."""

    success: bool
    speech: tuple[str, ...]
    reason: str = ""


class CommandServer:
    """Serves homebot's command action, parse service, event and speech topics."""

    def __init__(self, node: Node, *, parse: Callable[[str], dict[str, Any]],
                 carry_out: Callable[[str], CommandOutcome], events: EventLog,
                 namespace: str = "/homebot") -> None:
        self.node, self.parse, self.carry_out = node, parse, carry_out
        self.events_topic = node.publisher(f"{namespace}/events", "std_msgs/msg/String",
                                           RELIABLE_ALL_QOS)
        self.speech_topic = node.publisher(f"{namespace}/speech", "std_msgs/msg/String")
        self.parser = node.service(f"{namespace}/parse", "homebot_msgs/srv/Parse", self._parse,
                                   lambda reason: {"understood": False, "steps": "[]",
                                                   "error": reason})
        self.command = ActionServer(
            node, f"{namespace}/command", "homebot_msgs/action/Command", self._command,
            refuse=lambda reason: {"success": False, "speech": "", "reason": reason})
        self._arrivals = Arrivals(node, [self.parser.requests,
                                         *self.command.request_subscriptions()])
        self._goal: GoalContext | None = None
        events.listeners.append(self._publish)

    def spin_once(self, timeout: float = 0.1) -> int:
        """Answer what arrived (waiting up to ``timeout`` s for a request); how many."""
        self._arrivals.wait(timeout)
        return self.command.poll() + self.parser.poll() + self.command.poll()

    def _publish(self, event: Event) -> None:
        types = self.node.types
        self.events_topic.publish(types.new(
            "std_msgs/msg/String",
            data=json.dumps(event.to_dict(), sort_keys=True, ensure_ascii=False)))
        if event.kind == "speech":
            self.speech_topic.publish(types.new("std_msgs/msg/String",
                                                data=str(event.data.get("text", ""))))
        if event.kind == "skill.start" and self._goal is not None:
            arguments = ", ".join(f"{key}={value}"
                                  for key, value in dict(event.data.get("args", {})).items())
            self._goal.publish_feedback(step=f"{event.data.get('skill')}({arguments})")

    def _parse(self, request: Any) -> dict[str, Any]:
        parsed = self.parse(check_command(str(request.command), self.parser.name))
        understood = parsed.get("status") == "ok"
        return {"understood": understood,
                "steps": json.dumps(parsed.get("steps", []), ensure_ascii=False),
                "error": "" if understood else str(parsed.get("question") or
                                                   parsed.get("reason") or "")}

    def _command(self, goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        command = check_command(str(goal.command), self.command.name)
        self._goal = context
        try:
            outcome = self.carry_out(command)
        finally:
            self._goal = None
        return (GoalStatus.SUCCEEDED if outcome.success else GoalStatus.ABORTED,
                {"success": outcome.success, "speech": " ".join(outcome.speech),
                 "reason": outcome.reason})
