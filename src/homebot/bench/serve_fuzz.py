"""Malformed requests to the DDS servers: ``homebot sim serve`` and ``homebot ros serve``.

Each server runs as its own process on loopback. One client sends ``--requests`` malformed
requests to it, from a seeded generator, one after another, each waiting for its answer:

- ``sim serve``: ``RobotCall`` with unknown methods, arguments of the wrong shape (``[1]``
  to ``move_options``), deep nesting (20 000 levels), oversized, truncated or non-finite
  JSON, wrong field types, extra fields; ``NavigateToPose`` goals with NaN, infinite or
  absurd poses and foreign frames; cancel and get_result requests for made-up goals.
- ``ros serve``: ``/homebot/parse`` requests and ``/homebot/command`` goals that are empty,
  over-long, control characters, random Unicode or word salad; cancel and get_result
  requests for made-up goals.

A few requests (``--oversized`` in a thousand) are larger than DDS's sample limit; DDS drops
those unread, so they get no answer by design, and are counted apart. Every other request
must be answered. At the end the server must still be running and answer a valid request
rightly, and its resident memory is read after a warm-up and at the end: it must stay flat.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import count, seed
from homebot.errors import BenchmarkError
from homebot.transport import require_ros

__all__ = ["FuzzReport", "add_arguments", "fuzz_server", "run"]

_DOMAIN = 229  # the benchmark's own DDS domain, loopback only (bench transport has 230)
_WORDS = ("bring", "me", "the", "cola", "to", "kitchen", "and", "find", "a", "person",
          "go", "table", "it", "pick", "up", "him", "her", "zzq", "qux", "door", "open",
          "follow", "lamp", "put", "on", "tell", "what", "day", "sofa", "bedroom")
_METHODS = ("hands", "now", "pose", "move_to", "perceive_objects", "perceive_people",
            "grasp", "held", "release", "hand_over", "open_door", "door_is_open", "say", "ask",
            "request", "follow", "move_options", "last_move", "final_state")
#: A well-formed argument object per method, which the generator then breaks.
_TEMPLATES: dict[str, dict[str, Any]] = {
    "move_to": {"goal": {"x": 1.0, "y": 1.0, "theta": 0.0}, "avoid_doors": [],
                "escort": None},
    "perceive_objects": {"placement": "table"},
    "grasp": {"detection": {"label": "cola", "category": "drink", "handle": 1},
              "hand": "right"},
    "held": {"hand": "right"}, "release": {"hand": "right", "placement": "table"},
    "hand_over": {"hand": "right", "person": "operator"}, "open_door": {"door": "door"},
    "door_is_open": {"door": "door"}, "say": {"text": "hello"},
    "ask": {"person": "operator", "question": "what?"},
    "request": {"person": "operator", "request": "open_door", "target": "door"},
    "follow": {"person": "operator", "goal": None},
    "move_options": {"avoid_doors": [], "escort": None},
}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--requests", type=count("--requests", 1, 1_000_000), default=10_000,
                        help="malformed requests to each server (default 10000)")
    parser.add_argument("--warm-up", type=count("--warm-up", 0, 100_000), default=2000,
                        help="malformed requests before the first memory reading "
                             "(default 2000: the server's bounded caches fill by then)")
    parser.add_argument("--oversized", type=count("--oversized", 0, 1000), default=1,
                        help="requests per thousand larger than DDS's sample limit "
                             "(default 1)")
    parser.add_argument("--time-limit", type=count("--time-limit", 1, 7200), default=900,
                        help="seconds each server's run may take at most (default 900)")
    parser.add_argument("--only", choices=["all", "sim", "ros"], default="all",
                        help="fuzz one server only")
    parser.add_argument("--seed", type=seed, default=33)


@dataclass
class FuzzReport:
    """What one server went through and how it came out."""

    server: str
    requests: int = 0  #: malformed requests sent (warm-up included)
    answered: int = 0  #: of them, answered
    dropped_by_dds: int = 0  #: oversized ones sent, which DDS drops unanswered by design
    unanswered: int = 0  #: others that got no answer within the time out (should be 0)
    kinds: Counter[str] = field(default_factory=Counter)  #: requests by kind
    seconds: float = 0.0  #: wall time of the malformed requests
    rss_start_mb: float = 0.0  #: the server's resident memory after the warm-up
    rss_end_mb: float = 0.0  #: and at the end
    rss_series_mb: list[float] = field(default_factory=list)  #: after every 1000 requests
    alive: bool = False  #: the server process still runs at the end
    valid_answer: bool = False  #: and answered a valid request rightly
    log_lines: int = 0  #: lines the server logged (one per refused request)
    internal_errors: int = 0  #: requests that met a fault of the server (should be 0)

    def to_dict(self) -> dict[str, Any]:
        return {"server": self.server, "requests": self.requests, "answered": self.answered,
                "dropped_by_dds": self.dropped_by_dds, "unanswered": self.unanswered,
                "kinds": dict(sorted(self.kinds.items())), "seconds": round(self.seconds, 2),
                "rss_start_mb": round(self.rss_start_mb, 2),
                "rss_end_mb": round(self.rss_end_mb, 2),
                "rss_series_mb": [round(value, 1) for value in self.rss_series_mb],
                "rss_growth_mb": round(self.rss_end_mb - self.rss_start_mb, 2),
                "alive": self.alive, "valid_answer": self.valid_answer,
                "log_lines": self.log_lines, "internal_errors": self.internal_errors}


# ------------------------------------------------------------ the generator


class _Junk:
    """Malformed pieces, drawn from one seeded generator."""

    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng

    def pick(self, options: tuple[Any, ...] | list[Any]) -> Any:
        return options[int(self.rng.integers(len(options)))]

    def text(self) -> str:
        """A string no server should take as it is."""
        rng, kind = self.rng, int(self.rng.integers(7))
        if kind == 0:
            return str(self.pick(["", " ", "\t\n  ", "\u00a0", "\x00"]))
        if kind == 1:  # over-long (up to 64 kB)
            return "x" * int(rng.integers(1001, 65_536))
        if kind == 2:  # control characters mixed with words
            return "".join(chr(int(code)) if code < 32 else self.pick(_WORDS) + " "
                           for code in rng.integers(0, 64, int(rng.integers(1, 40))))
        if kind == 3:  # random Unicode (no lone surrogates: those are not UTF-8 at all)
            codes = rng.integers(1, 0x10FFFF, int(rng.integers(1, 200)))
            return "".join(chr(int(code)) for code in codes if not 0xD800 <= code <= 0xDFFF)
        if kind == 4:  # word salad, a few words over the limit or within it
            return " ".join(self.pick(_WORDS) for _ in range(int(rng.integers(1, 400))))
        if kind == 5:
            return self.nested()
        return json.dumps(self.value())

    def nested(self) -> str:
        depth = int(self.rng.integers(100, 20_000))
        opener, closer = self.pick([("[", "]"), ('{"a":', "}")])
        return str(opener) * depth + "1" + (closer * depth if self.rng.random() < 0.5 else "")

    def value(self) -> Any:
        """A JSON value of a random type, sometimes absurd."""
        return self.pick([None, True, -1, 2**70, 1e308, "x" * 300, [1], {"x": [[]]}, "",
                          [None] * 200, {"": None}, -0.0])

    def arguments(self, method: str) -> str:
        """A method's arguments, broken in one of many ways."""
        rng = self.rng
        template = _TEMPLATES.get(method)
        kind = int(rng.integers(9))
        if template is None or kind == 0:
            return self.pick(["[1]", "1", "null", "true", '"x"', "[]", "{", "{}}", "NaN",
                              '{"x": 1e999}', "\x00", ""]) if kind < 5 else self.text()
        data = json.loads(json.dumps(template))
        key = self.pick(sorted(data))
        if kind == 1:
            del data[key]
        elif kind == 2:
            data["extra"] = self.value()
        elif kind == 3:
            data[key] = self.value()
        elif kind == 4:
            data[key] = {"x": math.nan, "y": math.inf, "theta": 0.0}
        elif kind == 5:
            return json.dumps(data)[: int(rng.integers(1, 10))]  # truncated
        elif kind == 6:
            return json.dumps(data)[:-1] + ', "pad": "' + "x" * 20_000 + '"}'  # oversized
        elif kind == 7:
            return f'{{"{key}": {self.nested()}}}'
        else:  # well-formed, names the world lacks: the robot itself must say no
            data = {name: ("no_such_" + name if isinstance(item, str) else item)
                    for name, item in data.items()}
        return json.dumps(data, allow_nan=True)

    def number(self) -> float:
        return float(self.pick([math.nan, math.inf, -math.inf, 1e308, -1e308, 1e6, 0.0]))


# ------------------------------------------------------------ the servers


@dataclass
class _Server:
    """A server process and its log file."""

    name: str
    process: subprocess.Popen[bytes]
    log: Path

    def resident_mb(self) -> float:
        with open(f"/proc/{self.process.pid}/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
        raise BenchmarkError(f"no resident memory of {self.name} (is /proc there?)")


def _start(name: str, domain_id: int, folder: Path) -> _Server:
    log = folder / f"{name.replace(' ', '_')}.log"
    command = [sys.executable, "-c", "import sys; from homebot.cli import main; "
               "sys.exit(main())", *name.split(), "--seed", "1", "--domain-id",
               str(domain_id)]
    with log.open("wb") as handle:
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=handle)
    return _Server(name, process, log)


def _uuid(junk: _Junk) -> bytes:
    return bytes(int(value) for value in junk.rng.integers(0, 256, 16))


class _SimTarget:
    """Requests to ``homebot sim serve``."""

    name = "sim serve"

    def __init__(self, node: Any) -> None:
        from homebot.transport.actions import ActionClient

        self.node = node
        self.calls = node.client("/homebot/robot", "homebot_msgs/srv/RobotCall")
        self.navigate = ActionClient(node, "/navigate_to_pose",
                                     "nav2_msgs/action/NavigateToPose")

    def wait(self, timeout: float) -> bool:
        return self.calls.wait_for_server(timeout) and self.navigate.wait_for_server(timeout)

    def request(self, junk: _Junk, timeout: float) -> tuple[str, bool]:
        """Send one malformed request; its kind and whether it was answered."""
        from homebot.geometry import Pose
        from homebot.transport.messages import pose_stamped

        kind = int(junk.rng.integers(10))
        if kind < 6:
            method = junk.pick(_METHODS) if kind else junk.text()
            return "robot_call", self._answered(
                self.calls, timeout, method=method, arguments=junk.arguments(method))
        if kind < 8:
            types = self.node.types
            goal = pose_stamped(types, Pose(0.0, 0.0, 0.0), 0.0,
                                junk.pick(["map", "odom", "/map", "", "x" * 300]))
            goal.pose.position.x, goal.pose.position.y = junk.number(), junk.number()
            goal.pose.orientation.w = junk.number()
            return "navigate_goal", _goal_answered(self.navigate, timeout,
                                                   pose=goal, behavior_tree=junk.text())
        return _cancel_or_result(self.navigate, junk, timeout)

    @staticmethod
    def _answered(client: Any, timeout: float, **fields: Any) -> bool:
        from homebot.errors import TransportError

        try:
            client.call(timeout, **fields)
        except TransportError:
            return False
        return True

    def valid(self, timeout: float) -> bool:
        """A valid call answered rightly: the robot's hands and its pose."""
        hands = json.loads(self.calls.call(timeout, method="hands", arguments="{}").result)
        pose = json.loads(self.calls.call(timeout, method="pose", arguments="{}").result)
        return bool(hands) and set(pose) == {"x", "y", "theta"}


class _RosTarget:
    """Requests to ``homebot ros serve``."""

    name = "ros serve"

    def __init__(self, node: Any) -> None:
        from homebot.transport.actions import ActionClient

        self.parse = node.client("/homebot/parse", "homebot_msgs/srv/Parse")
        self.command = ActionClient(node, "/homebot/command", "homebot_msgs/action/Command")

    def wait(self, timeout: float) -> bool:
        return self.parse.wait_for_server(timeout) and self.command.wait_for_server(timeout)

    def request(self, junk: _Junk, timeout: float) -> tuple[str, bool]:
        kind = int(junk.rng.integers(10))
        if kind < 6:
            return "parse", _SimTarget._answered(self.parse, timeout, command=junk.text())
        if kind < 8:
            text = junk.text()
            if text.isprintable() and text.strip() and len(text) <= 1000:
                text += "\x07"  # a goal the language layer could take would run a task
            return "command_goal", _goal_answered(self.command, timeout, command=text)
        return _cancel_or_result(self.command, junk, timeout)

    def valid(self, timeout: float) -> bool:
        reply = self.parse.call(timeout, command="bring me a cola")
        return bool(reply.understood) and json.loads(reply.steps)[0]["skill"] == "find_object"


def _goal_answered(action: Any, timeout: float, **goal: Any) -> bool:
    """A malformed goal: accepted, then its result (ABORTED with a reason) comes."""
    from homebot.errors import TransportError

    try:
        goal_id = action.send(timeout, **goal)
        if goal_id is not None:  # a rejected goal is answered too
            action.result(goal_id, timeout)
    except TransportError:
        return False
    return True


def _cancel_or_result(action: Any, junk: _Junk, timeout: float) -> tuple[str, bool]:
    """A cancel or a result request for a goal the server never had."""
    from homebot.errors import TransportError
    from homebot.transport.actions import GoalStatus

    goal_id = _uuid(junk)
    try:
        if junk.rng.random() < 0.5:
            action.cancel(goal_id, timeout)
            return "cancel", True
        status, _result = action.result(goal_id, timeout)
    except TransportError:
        return "get_result", False
    return "get_result", status is GoalStatus.UNKNOWN


def _oversized(target: Any, size: int) -> None:
    """Send a request over DDS's sample limit (the server's DDS drops it unread)."""
    if isinstance(target, _SimTarget):
        target.calls.send(method="say", arguments="x" * size)
    else:
        target.parse.send(command="x" * size)


def fuzz_server(server_name: str, *, requests: int, seed: int, domain_id: int,
                warm_up: int = 2000, oversized: int = 1, time_limit: float = 900.0,
                progress: Callable[[int], None] | None = None,
                first: Callable[[Any], None] | None = None) -> FuzzReport:
    """Start ``server_name`` ("sim serve" or "ros serve"), send it ``requests`` malformed
    requests (``warm_up`` of them before the first memory reading), then a valid one.
    ``first(node)``, when given, runs once the server answers, before the malformed
    requests, with this side's node (a test's own cases, on the same server)."""
    require_ros()
    from homebot.transport.node import MAX_SAMPLE, Node, TransportSettings, loopback

    junk = _Junk(np.random.default_rng(seed))
    report = FuzzReport(server_name)
    with tempfile.TemporaryDirectory(prefix="homebot-fuzz-") as folder:
        server = _start(server_name, domain_id, Path(folder))
        try:
            # This client's own DDS lets through what the server's refuses as too big.
            settings = loopback(domain_id)
            node = Node(TransportSettings(settings.domain_id, settings.interface,
                                          settings.peers, max_sample=4 * MAX_SAMPLE))
            target = _SimTarget(node) if server_name == "sim serve" else _RosTarget(node)
            if not target.wait(120.0) or not target.valid(60.0):
                raise BenchmarkError(f"{server_name} did not start (log: "
                                     f"{server.log.read_text(errors='replace')[-500:]})")
            if first is not None:
                first(node)
            deadline = time.monotonic() + time_limit
            began = time.perf_counter()
            for index in range(requests):
                if index == min(warm_up, requests - 1):
                    report.rss_start_mb = server.resident_mb()
                if time.monotonic() > deadline or server.process.poll() is not None:
                    break
                report.requests += 1
                if junk.rng.random() * 1000 < oversized:
                    _oversized(target, MAX_SAMPLE + 1024)
                    report.dropped_by_dds += 1
                    report.kinds["oversized"] += 1
                    continue
                kind, answered = target.request(junk, 10.0)
                report.kinds[kind] += 1
                report.answered += answered
                report.unanswered += not answered
                if index % 1000 == 999:
                    report.rss_series_mb.append(server.resident_mb())
                    if progress is not None:
                        progress(index + 1)
            report.seconds = time.perf_counter() - began
            report.alive = server.process.poll() is None
            report.valid_answer = report.alive and target.valid(30.0)
            report.rss_end_mb = server.resident_mb() if report.alive else 0.0
        finally:
            server.process.kill()
            server.process.wait(10)
        log = server.log.read_bytes()
        report.log_lines = len(log.splitlines())
        report.internal_errors = log.count(b": internal error on a request")
    return report


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Fuzz each server in turn; the figures of each."""
    names = ["sim serve", "ros serve"] if args.only == "all" else [f"{args.only} serve"]
    reports = []
    for offset, name in enumerate(names):
        progress = None if console is None else (
            lambda done, name=name: console.print(f"  {name}: {done} requests"))
        reports.append(fuzz_server(name, requests=args.requests, seed=args.seed + offset,
                                   domain_id=_DOMAIN - offset, warm_up=args.warm_up,
                                   oversized=args.oversized, time_limit=args.time_limit,
                                   progress=progress))
    figures = {"benchmark": "serve_fuzz", "servers": [report.to_dict() for report in reports],
               "seed": args.seed}
    if console is not None:
        table = Table(title=f"malformed requests (seed {args.seed})")
        for column in ("server", "requests", "answered", "dropped by DDS", "unanswered",
                       "seconds", "RSS start MB", "RSS end MB", "alive", "valid answer"):
            table.add_column(column)
        for report in reports:
            row = report.to_dict()
            table.add_row(report.server, str(row["requests"]), str(row["answered"]),
                          str(row["dropped_by_dds"]), str(row["unanswered"]),
                          str(row["seconds"]), str(row["rss_start_mb"]),
                          str(row["rss_end_mb"]), str(row["alive"]), str(row["valid_answer"]))
        console.print(table)
    return figures
