"""ROS 2's names on the DDS wire: topics, service and action topics, and QoS profiles.

A ROS 2 topic ``/scan`` is the DDS topic ``rt/scan``; a service ``/parse`` is the request
topic ``rq/parseRequest`` and the reply topic ``rr/parseReply``; an action ``/navigate_to_pose``
is three services (``_action/send_goal``, ``_action/get_result``, ``_action/cancel_goal``)
and two topics (``_action/feedback``, ``_action/status``) under its name. QoS profiles are
rmw's: the default (reliable, volatile, keep last 10), sensor data (best effort, keep last 5),
services (reliable, volatile, keep last 10), the ``map`` topic as ``map_server`` offers it
(reliable, transient local, keep last 1), and action status (reliable, transient local).

Names follow ROS 2's rules (``check_name``, ``check_frame``): letters, digits, ``_`` and
``/``; no token starting with a digit, no ``//`` or ``__``, no trailing ``/``; at most
``MAX_NAME_LENGTH`` characters. A name that breaks them is refused here with the rule it
breaks, before DDS sees it (DDS would refuse some with a bare ``DDSException``, or accept a
name no ROS 2 node can subscribe to).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import StrEnum

from cyclonedds.core import Policy, Qos
from cyclonedds.util import duration

__all__ = [
    "ACTION_SERVICES",
    "ACTION_STATUS_QOS",
    "ACTION_TOPICS",
    "DEFAULT_QOS",
    "MAP_QOS",
    "RELIABLE_ALL_QOS",
    "SENSOR_QOS",
    "SERVICE_QOS",
    "Durability",
    "QosProfile",
    "Reliability",
    "action_service",
    "action_topic",
    "check_frame",
    "check_name",
    "reply_topic",
    "request_topic",
    "topic",
]

ACTION_SERVICES = ("send_goal", "get_result", "cancel_goal")
ACTION_TOPICS = ("feedback", "status")
#: rmw's limit on a topic name (255) less the longest prefix and suffix it adds.
MAX_NAME_LENGTH = 247
_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def check_name(name: object) -> str:
    """``name`` when it is a valid ROS 2 topic, service or action name, else ``ValueError``
    saying which rule it breaks. Absolute (``/scan``) or relative (``scan``): homebot has no
    node namespace, so both mean the same; ``~`` and ``{}`` substitutions are not offered."""
    if not isinstance(name, str):
        raise ValueError(f"a ROS 2 name is text, not {type(name).__name__}")
    shown = ascii(name[:60] + ("..." if len(name) > 60 else ""))
    if not name.strip("/"):
        raise ValueError("a ROS 2 name must not be empty")
    if len(name) > MAX_NAME_LENGTH:
        raise ValueError(f"the ROS 2 name {shown} has {len(name)} characters; "
                         f"keep it to {MAX_NAME_LENGTH}")
    if name.endswith("/") or "//" in name or "__" in name:
        raise ValueError(f"the ROS 2 name {shown} ends in '/' or holds '//' or '__'")
    for token in name.removeprefix("/").split("/"):
        if not _TOKEN.fullmatch(token):
            raise ValueError(f"the ROS 2 name {shown} is not letters, digits, '_' and '/' "
                             f"with no part starting with a digit (part {token!a})")
    return name


def check_frame(frame: object) -> str:
    """``frame`` when it is a valid tf2 frame id (a ROS 2 name without a leading ``/``)."""
    if isinstance(frame, str) and frame.startswith("/"):
        raise ValueError(f"the frame id {frame[:60]!a} starts with '/'; tf2 frame ids "
                         "do not (write it without)")
    return check_name(frame)


def _relative(name: str) -> str:
    return check_name(name).lstrip("/")


def topic(name: str) -> str:
    """The DDS topic of ROS 2 topic ``name``: ``/scan`` -> ``rt/scan``."""
    return f"rt/{_relative(name)}"


def request_topic(service: str) -> str:
    """The DDS request topic of a service: ``/parse`` -> ``rq/parseRequest``."""
    return f"rq/{_relative(service)}Request"


def reply_topic(service: str) -> str:
    """The DDS reply topic of a service: ``/parse`` -> ``rr/parseReply``."""
    return f"rr/{_relative(service)}Reply"


def action_service(action: str, part: str) -> str:
    """The ROS 2 service of an action's part: ``(/navigate_to_pose, send_goal)``."""
    if part not in ACTION_SERVICES:
        raise ValueError(f"an action service is one of {ACTION_SERVICES}, not {part!r}")
    return f"/{_relative(action)}/_action/{part}"


def action_topic(action: str, part: str) -> str:
    """The ROS 2 topic of an action's feedback or status."""
    if part not in ACTION_TOPICS:
        raise ValueError(f"an action topic is one of {ACTION_TOPICS}, not {part!r}")
    return f"/{_relative(action)}/_action/{part}"


class Reliability(StrEnum):
    RELIABLE = "reliable"
    BEST_EFFORT = "best_effort"


class Durability(StrEnum):
    VOLATILE = "volatile"
    TRANSIENT_LOCAL = "transient_local"


@dataclass(frozen=True, slots=True)
class QosProfile:
    """A ROS 2 QoS profile. ``depth`` 0 keeps all samples (no loss at reliable QoS)."""

    reliability: Reliability = Reliability.RELIABLE
    durability: Durability = Durability.VOLATILE
    depth: int = 10

    def to_dds(self) -> Qos:
        """The cyclonedds QoS of this profile."""
        reliability = (Policy.Reliability.Reliable(duration(milliseconds=100))
                       if self.reliability is Reliability.RELIABLE
                       else Policy.Reliability.BestEffort)
        durability = (Policy.Durability.TransientLocal
                      if self.durability is Durability.TRANSIENT_LOCAL
                      else Policy.Durability.Volatile)
        history = Policy.History.KeepLast(self.depth) if self.depth else Policy.History.KeepAll
        return Qos(reliability, durability, history)


#: rmw's named profiles.
DEFAULT_QOS = QosProfile()
SENSOR_QOS = QosProfile(Reliability.BEST_EFFORT, depth=5)
SERVICE_QOS = QosProfile()
MAP_QOS = QosProfile(durability=Durability.TRANSIENT_LOCAL, depth=1)
ACTION_STATUS_QOS = QosProfile(durability=Durability.TRANSIENT_LOCAL, depth=1)
#: Reliable, keep all: nothing is lost while the reader keeps up within the writer's buffers.
RELIABLE_ALL_QOS = QosProfile(depth=0)
