"""A ROS 2 node without ROS: a DDS participant with publishers, subscriptions and services.

Everything is single-threaded and explicit: a subscription is read when its owner asks,
a service server answers what has arrived when ``poll`` is called, a client waits for
its reply with a timeout. Waiting is always a DDS wait set with a deadline, never a sleep.

``TransportSettings`` chooses the DDS domain and the network: ``loopback(domain_id)``
keeps everything on 127.0.0.1 (tests, several processes on one machine); a real robot
names its network interface and leaves multicast discovery on.

A server survives every request: a sample DDS cannot read is dropped (``Subscription.take``),
a handler's error becomes the reply its ``refuse`` function builds, and both are logged
(``homebot.transport`` logger, one line each); a client that reads no replies is waited for
once, not at every request (``ReplyRoute``). ``TransportSettings.max_sample`` caps the
serialised size of any sample in either direction, so a huge request is dropped by DDS before
it is read.
"""

from __future__ import annotations

import atexit
import logging
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from cyclonedds.core import (
    DDSException,
    DDSStatus,
    InstanceState,
    ReadCondition,
    SampleState,
    ViewState,
    WaitSet,
)
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.internal import InvalidSample
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from homebot.errors import HomebotError, TransportError
from homebot.transport.naming import (
    DEFAULT_QOS,
    SERVICE_QOS,
    QosProfile,
    reply_topic,
    request_topic,
)
from homebot.transport.naming import topic as dds_topic
from homebot.transport.types import MessageTypes

__all__ = [
    "Arrivals",
    "Node",
    "Publisher",
    "ReplyRoute",
    "ServiceClient",
    "ServiceServer",
    "Subscription",
    "TransportError",
    "TransportSettings",
    "loopback",
    "refusal",
    "shown",
]

T = TypeVar("T")

log = logging.getLogger("homebot.transport")

#: Bytes of a serialised sample, in or out: above any message homebot sends or takes (a
#: 40 x 40 m map at 5 cm is 640 kB, a 320 x 240 point cloud 1.2 MB), far below what would
#: strain the robot's memory. Larger samples are dropped by DDS unread (MaxSampleSize).
MAX_SAMPLE = 4 * 1024 * 1024


def shown(text: object, limit: int = 80) -> str:
    """``text`` fit for one log or error line: escaped (no control characters reach a
    terminal) and cut to ``limit`` characters with its full length."""
    value = str(text)
    if len(value) <= limit:
        return ascii(value)
    return f"{value[:limit]!a}... ({len(value)} characters)"


@dataclass(frozen=True, slots=True)
class TransportSettings:
    """Which DDS domain and network a node uses.

    ``interface``: the network interface by name (``lo``, ``eth0``, ``wlan0``) or None for
    cyclonedds' choice. ``peers``: unicast discovery addresses (loopback has no multicast).
    ``lease``: seconds after which a silent participant counts as gone.
    """

    domain_id: int = 0
    interface: str | None = None
    peers: tuple[str, ...] = ()
    lease: float = 1.0
    max_sample: int = MAX_SAMPLE

    def __post_init__(self) -> None:
        if not 0 <= self.domain_id <= 232:
            raise TransportError(f"ROS_DOMAIN_ID {self.domain_id} is outside 0..232; "
                                 "choose the robot's domain id (0 unless set otherwise)")

    def config(self) -> str:
        """The cyclonedds XML configuration of these settings."""
        general = ""
        if self.interface:
            general += f'<Interfaces><NetworkInterface name="{self.interface}"/></Interfaces>'
        if self.peers:
            general += "<AllowMulticast>false</AllowMulticast>"
        discovery = f"<LeaseDuration>{self.lease:g}s</LeaseDuration>"
        if self.peers:
            peers = "".join(f'<Peer address="{peer}"/>' for peer in self.peers)
            discovery += (f"<ParticipantIndex>auto</ParticipantIndex>"
                          f"<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>"
                          f"<Peers>{peers}</Peers>")
        return (f'<CycloneDDS><Domain id="any"><General>{general}</General>'
                f"<Discovery>{discovery}</Discovery>"
                f"<Internal><MaxSampleSize>{self.max_sample}B</MaxSampleSize></Internal>"
                "</Domain></CycloneDDS>")


def loopback(domain_id: int) -> TransportSettings:
    """Settings for processes on this machine only: the loopback interface, unicast discovery."""
    return TransportSettings(domain_id, interface="lo", peers=("127.0.0.1",))


def _deadline(timeout: float) -> float:
    return time.monotonic() + timeout


def _left(deadline: float) -> float:
    return max(0.0, deadline - time.monotonic())


def _wait(waitset: WaitSet, seconds: float) -> None:
    waitset.wait(duration(seconds=max(seconds, 0.0)))


class Publisher(Generic[T]):
    """Publishes on one ROS 2 topic."""

    def __init__(self, node: Node, name: str, struct: type[T], qos: QosProfile) -> None:
        self.name = name
        self.writer: DataWriter[T] = DataWriter(node.participant, node.topic(name, struct),
                                                qos=qos.to_dds())

    def publish(self, message: T) -> None:
        self.writer.write(message)

    def subscribers(self) -> int:
        """How many readers are matched now."""
        return len(self.writer.get_matched_subscriptions())

    def wait_for_subscribers(self, count: int, timeout: float) -> bool:
        """Wait until ``count`` readers are matched (discovery), at most ``timeout`` s."""
        return _wait_matched(self.writer, DDSStatus.PublicationMatched,
                             lambda: self.subscribers() >= count, timeout)


class Subscription(Generic[T]):
    """Receives one ROS 2 topic; read it with ``take`` or ``wait``."""

    def __init__(self, node: Node, name: str, struct: type[T], qos: QosProfile) -> None:
        self.name = name
        self.reader: DataReader[T] = DataReader(node.participant, node.topic(name, struct),
                                                qos=qos.to_dds())
        self._condition = ReadCondition(self.reader, SampleState.NotRead | ViewState.Any |
                                        InstanceState.Any)
        self._waitset = WaitSet(node.participant)
        self._waitset.attach(self._condition)

    def take(self, limit: int = 256) -> list[T]:
        """Every sample that arrived since the last take (up to ``limit``).

        A sample that cannot be read (bytes that are not the type's CDR, text that is not
        UTF-8: a foreign or hostile writer) is dropped and logged, and so are the samples
        taken with it; the samples after it are read on the next take."""
        try:
            samples = self.reader.take(N=limit)
        except DDSException:
            raise  # DDS itself failed (a deleted reader): no sample's fault
        except Exception as error:  # any decoding error of a foreign sample
            log.warning("%s: dropped unreadable samples (%s: %s)", self.name,
                        type(error).__name__, shown(error))
            return []
        # Invalid samples only tell of a writer's instance going away (unregister, dispose).
        return [sample for sample in samples if not isinstance(sample, InvalidSample)]

    def wait(self, timeout: float) -> list[T]:
        """Wait up to ``timeout`` s for at least one sample; the samples (maybe none)."""
        samples = self.take()
        if not samples:
            _wait(self._waitset, timeout)
            samples = self.take()
        return samples

    def publishers(self) -> int:
        return len(self.reader.get_matched_publications())

    def wait_for_publishers(self, count: int, timeout: float) -> bool:
        return _wait_matched(self.reader, DDSStatus.SubscriptionMatched,
                             lambda: self.publishers() >= count, timeout)


class Arrivals:
    """Waits until any of several subscriptions has a sample: a server that offers several
    services and actions sleeps on all of them at once, so none waits for another's timeout."""

    def __init__(self, node: Node, subscriptions: list[Subscription[Any]]) -> None:
        self._waitset = WaitSet(node.participant)
        for subscription in subscriptions:
            self._waitset.attach(ReadCondition(
                subscription.reader, SampleState.NotRead | ViewState.Any | InstanceState.Any))

    def wait(self, timeout: float) -> None:
        """Return when a sample has come to any of them, or after ``timeout`` s."""
        _wait(self._waitset, timeout)


def _wait_matched(entity: DataWriter[Any] | DataReader[Any], status: int,
                  done: Callable[[], bool], timeout: float) -> bool:
    entity.set_status_mask(status)
    waitset = WaitSet(entity.participant)  # type: ignore[arg-type]
    waitset.attach(entity)
    deadline = _deadline(timeout)
    while not done():
        left = _left(deadline)
        if left <= 0:
            return False
        _wait(waitset, min(left, 0.05))
        if status == DDSStatus.PublicationMatched:
            entity.get_publication_matched_status()  # type: ignore[union-attr]
        else:
            entity.get_subscription_matched_status()  # type: ignore[union-attr]
    waitset.detach(entity)
    return True


class ServiceServer:
    """Answers a ROS 2 service: ``handler(request) -> response`` (the service's fields).

    A request the handler raises on is answered with ``refuse(reason)`` (the service's
    fields for an error) and logged; the server goes on. A ``HomebotError`` is a bad
    request and its message the reason; any other error is a fault of the server, logged
    with its traceback and answered as an internal error."""

    def __init__(self, node: Node, name: str, service: str,
                 handler: Callable[[Any], dict[str, Any]],
                 refuse: Callable[[str], dict[str, Any]]) -> None:
        self.name = name
        self.handler, self.refuse = handler, refuse
        self.refused = 0  #: requests answered with an error so far
        self._reply_struct: Any = node.types.reply_struct(service)
        self.requests = Subscription(node, request_topic(name),
                                     node.types.request_struct(service), SERVICE_QOS)
        self.replies = Publisher(node, reply_topic(name), self._reply_struct, SERVICE_QOS)
        self.route = ReplyRoute(self.requests, self.replies)

    def poll(self, timeout: float = 0.0) -> int:
        """Answer the requests that arrived (waiting up to ``timeout`` s); how many."""
        requests = self.requests.wait(timeout) if timeout else self.requests.take()
        for request in requests:
            try:
                fields = self.handler(request)
            except Exception as error:  # no request may stop the server
                self.refused += 1
                fields = self.refuse(refusal(self.name, error))
            self.route.ready(request)
            self.replies.publish(self._reply_struct(
                client_guid=request.client_guid, sequence=request.sequence,
                **fields))
        return len(requests)


def refusal(name: str, error: Exception) -> str:
    """Why a request to ``name`` was refused, logged: a ``HomebotError`` is the request's
    fault (its message says what to fix); anything else the server's (with a traceback)."""
    if isinstance(error, HomebotError):
        log.warning("%s: refused a request: %s", name, error)
        return str(error)
    log.error("%s: internal error on a request", name, exc_info=error)
    return f"internal error of the server ({type(error).__name__}); see its log"


class ReplyRoute:
    """Whether a request's sender hears replies yet, waiting for it if need be.

    Discovery runs each way on its own, and a reply written before the client's reply
    reader is matched would be lost, so the server waits (at most ``timeout`` s) until the
    reply writer has matched a reader of the participant that sent the request, as
    rmw_cyclonedds does. A participant that sends requests but never reads replies (a broken
    or hostile client) is waited for once; after that its requests are answered without
    waiting, so it cannot slow the server down for anyone (at most ``MAX_DEAF`` are kept)."""

    MAX_DEAF = 1000

    def __init__(self, requests: Subscription[Any], replies: Publisher[Any],
                 timeout: float = 5.0) -> None:
        self.requests, self.replies, self.timeout = requests, replies, timeout
        self._deaf: dict[Any, None] = {}  # participants that never read replies, oldest first
        self._senders: dict[int, Any] = {}  # request writer handle -> its participant
        self._readers: tuple[int, ...] = ()  # the reply readers matched when last looked
        self._hearing: set[Any] = set()  # and their participants

    def ready(self, request: Any) -> bool:
        """Wait until the sender of ``request`` hears replies; whether it does."""
        sender = self._sender(request)
        if sender is None:  # the sender is gone already: nothing to wait for
            return False
        if self._hears(sender):
            self._deaf.pop(sender, None)
            return True
        if sender in self._deaf:
            return False
        if _wait_matched(self.replies.writer, DDSStatus.PublicationMatched,
                         lambda: self._hears(sender), self.timeout):
            return True
        self._deaf[sender] = None
        while len(self._deaf) > self.MAX_DEAF:
            del self._deaf[next(iter(self._deaf))]
        log.warning("%s: a participant sends requests but reads no replies; its replies go "
                    "unheard", self.requests.name)
        return False

    def _sender(self, request: Any) -> Any:
        """The participant that wrote ``request`` (None when no longer known)."""
        try:
            handle = request.sample_info.publication_handle
            if handle not in self._senders:
                writer = self.requests.reader.get_matched_publication_data(handle)
                if writer is None:
                    return None
                if len(self._senders) >= self.MAX_DEAF:
                    self._senders.clear()  # looked up again as needed
                self._senders[handle] = writer.participant_key
        except (AttributeError, DDSException):
            return None
        return self._senders[handle]

    def _hears(self, participant: Any) -> bool:
        writer = self.replies.writer
        readers = tuple(writer.get_matched_subscriptions())
        if readers != self._readers:  # looked up again only when the matched readers change
            self._readers, self._hearing = readers, set()
            for handle in readers:
                try:
                    reader = writer.get_matched_subscription_data(handle)
                except DDSException:  # matched a moment ago, gone now
                    continue
                if reader is not None:
                    self._hearing.add(reader.participant_key)
        return participant in self._hearing


class ServiceClient:
    """Calls a ROS 2 service and waits for the reply."""

    def __init__(self, node: Node, name: str, service: str) -> None:
        self.name = name
        self._request_struct: Any = node.types.request_struct(service)
        self.requests = Publisher(node, request_topic(name), self._request_struct, SERVICE_QOS)
        self.replies = Subscription(node, reply_topic(name), node.types.reply_struct(service),
                                    SERVICE_QOS)
        self._guid = int.from_bytes(os.urandom(8), "little")
        self._sequence = 0

    def ready(self) -> bool:
        """Whether a server is there (its request reader and reply writer are matched)."""
        return self.requests.subscribers() > 0 and self.replies.publishers() > 0

    def wait_for_server(self, timeout: float) -> bool:
        return (self.requests.wait_for_subscribers(1, timeout)
                and self.replies.wait_for_publishers(1, timeout))

    def send(self, **fields: Any) -> int:
        """Send a request; its sequence number."""
        self._sequence += 1
        self.requests.publish(self._request_struct(client_guid=self._guid,
                                                   sequence=self._sequence, **fields))
        return self._sequence

    def receive(self, sequence: int, timeout: float,
                alive: Callable[[], bool] | None = None) -> Any:
        """The reply to request ``sequence``; raises ``TransportError`` on timeout or when
        the server goes away (``alive`` is checked between waits of at most 0.1 s)."""
        deadline = _deadline(timeout)
        replies = self.replies.take()
        while True:
            for reply in replies:
                if reply.client_guid == self._guid and reply.sequence == sequence:
                    return reply
            left = _left(deadline)
            if left <= 0:
                raise TransportError(f"service {self.name}: no reply within {timeout:g} s")
            if not self.ready() or (alive is not None and not alive()):
                raise TransportError(f"service {self.name}: the server went away")
            replies = self.replies.wait(min(left, 0.1))

    def call(self, timeout: float = 5.0, **fields: Any) -> Any:
        """Send a request and wait for its reply."""
        return self.receive(self.send(**fields), timeout)


# cyclonedds allows one configured Domain per id in a process; nodes of one process share it.
_DOMAINS: dict[int, tuple[TransportSettings, Domain]] = {}


@atexit.register
def _leave_domains() -> None:
    """Delete the process's DDS domains (and with them every participant, reader and
    writer) while the interpreter still runs: left to the garbage collector at
    interpreter teardown, a deletion could wait for ever on DDS's own threads, and the
    process never exited (one run of the transport tests in three)."""
    for _, domain in _DOMAINS.values():
        domain.__del__()  # cyclonedds deletes an entity (and its children) only here
    _DOMAINS.clear()


def _domain(settings: TransportSettings) -> Domain:
    known = _DOMAINS.get(settings.domain_id)
    if known is None:
        known = (settings, Domain(settings.domain_id, settings.config()))
        _DOMAINS[settings.domain_id] = known
    elif known[0] != settings:
        raise TransportError(f"DDS domain {settings.domain_id} is already set up in this process "
                             "with other settings; use one interface per domain id")
    return known[1]


class Node:
    """A DDS participant that speaks ROS 2: typed topics, services, actions."""

    def __init__(self, settings: TransportSettings, types: MessageTypes | None = None) -> None:
        self.settings = settings
        self.types = types or MessageTypes()
        try:
            self.domain = _domain(settings)
            self.participant = DomainParticipant(settings.domain_id)
        except DDSException as error:
            raise TransportError(f"cannot join DDS domain {settings.domain_id} on interface "
                                 f"{settings.interface or 'default'} ({error}); check the "
                                 "interface name (ip link) and the domain id") from None
        self._topics: dict[str, Topic[Any]] = {}

    def topic(self, name: str, struct: type[Any]) -> Topic[Any]:
        """The DDS topic ``name`` (already in DDS form: ``rt/…``, ``rq/…``), made once."""
        made = self._topics.get(name)
        if made is None:
            made = Topic(self.participant, name, struct)
            self._topics[name] = made
        return made

    def publisher(self, name: str, message: str, qos: QosProfile = DEFAULT_QOS) -> Publisher[Any]:
        """A publisher of ROS 2 topic ``name`` with messages of type ``message``."""
        return Publisher(self, dds_topic(name), self.types.struct(message), qos)

    def subscription(self, name: str, message: str,
                     qos: QosProfile = DEFAULT_QOS) -> Subscription[Any]:
        return Subscription(self, dds_topic(name), self.types.struct(message), qos)

    def service(self, name: str, service: str, handler: Callable[[Any], dict[str, Any]],
                refuse: Callable[[str], dict[str, Any]]) -> ServiceServer:
        """A server of ``service`` at ``name``; ``refuse(reason)`` is its error reply."""
        return ServiceServer(self, name, service, handler, refuse)

    def client(self, name: str, service: str) -> ServiceClient:
        return ServiceClient(self, name, service)
