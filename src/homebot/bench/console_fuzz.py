"""The web console under bad requests: a 100 MB unauthenticated POST, and 10 000 malformed ones.

``homebot serve`` runs in a process of its own on loopback (uvicorn, symbolic home, as fast
as possible), so its resident memory is its own (read from ``/proc/PID/status``). First,
unauthenticated POSTs of ``--big-mb`` MB (declared by Content-Length, then chunked) and an
authenticated one over the body cap: the figure is the server's growth in resident set size
and in its peak (VmHWM). Then a seeded generator sends ``--requests`` malformed requests over
HTTP (keep-alive, reconnecting where the server closes): no token or a wrong one, unknown
paths and methods, bodies that are not JSON, too big or too deep, wrong types, NaN and
infinities, long and control-character strings, extra fields, forged sessions, steps naming
no skill or bad arguments (``--only KIND``: one kind alone). The figures: answers by status
(a 5xx is a fault), time, the server's memory after a warm-up, at each tenth and at the end,
the events it had logged at each tenth (the few requests that are well formed run tasks,
and the console's bounded log fills), and whether it still answers.
"""

from __future__ import annotations

import argparse
import contextlib
import http.client
import json
import os
import random
import socket
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from rich.console import Console as Terminal

from homebot.bench.arguments import count, seed

__all__ = ["KINDS", "BadRequest", "ServedConsole", "add_arguments", "big_post", "fuzz",
           "malformed_requests", "run", "served_console"]

_TOKEN = "console-fuzz-token"
_START_TIMEOUT = 60.0  #: wall seconds for the server to listen
_WARM_UP = 300  #: requests before the first memory reading
#: the kinds of malformed request, each drawn with its share (steps twice as often)
KINDS = ("no_token", "wrong_token", "no_session", "forged_session", "unknown_path",
         "wrong_method", "not_json", "odd_json", "control", "drive", "command", "steps",
         "steps", "query")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--requests", type=count("--requests", 1, 1_000_000), default=10_000,
                        help="malformed requests to send (default 10000)")
    parser.add_argument("--big-mb", type=count("--big-mb", 0, 2000), default=100,
                        help="size of the unauthenticated POSTs in MB (0: none; default 100)")
    parser.add_argument("--seed", type=seed, default=0, help="seed of the generator")
    parser.add_argument("--only", choices=sorted(set(KINDS)), default=None, metavar="KIND",
                        help="send malformed requests of this kind only (one of "
                             f"{', '.join(sorted(set(KINDS)))}; default: all, mixed)")
    parser.add_argument("--stopped", action="store_true",
                        help="press the emergency stop first: no request can start a task, "
                             "so the memory is the request handling's alone")


def run(args: argparse.Namespace, console: Terminal | None = None) -> dict[str, Any]:
    figures: dict[str, Any] = {}
    with served_console() as server:
        if args.big_mb:
            size = args.big_mb * 1024 * 1024
            figures["unauthenticated_post"] = big_post(server, size, chunked=False)
            figures["unauthenticated_chunked_post"] = big_post(server, size, chunked=True)
            figures["authenticated_post_over_the_cap"] = big_post(server, size, chunked=False,
                                                                  token=_TOKEN)
        kinds = KINDS if args.only is None else (args.only,)
        figures["fuzz"] = fuzz(server, args.requests, args.seed, kinds, stopped=args.stopped)
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}", highlight=False)
    return {"benchmark": "console_fuzz", "figures": figures}


# ---------------------------------------------------------------- the served console


@dataclass
class ServedConsole:
    """``homebot serve`` in a process of its own, listening on loopback."""

    process: subprocess.Popen[bytes]
    port: int
    token: str

    def memory_mb(self) -> tuple[float, float]:
        """The server's resident set size and its peak so far (VmRSS, VmHWM), in MB."""
        values: dict[str, float] = {}
        with open(f"/proc/{self.process.pid}/status", encoding="ascii") as status:
            for line in status:
                key, _, rest = line.partition(":")
                if key in ("VmRSS", "VmHWM"):
                    values[key] = int(rest.split()[0]) / 1024
        return values["VmRSS"], values["VmHWM"]

    def state(self) -> dict[str, Any] | None:
        """The console's state (a good request), or None when it does not answer with it."""
        connection = http.client.HTTPConnection("127.0.0.1", self.port, timeout=30)
        try:
            connection.request("GET", "/api/state", headers={"X-Homebot-Token": self.token})
            response = connection.getresponse()
            body = response.read()
            return dict(json.loads(body)) if response.status == 200 else None
        except (OSError, ValueError):
            return None
        finally:
            connection.close()

    def events_logged(self) -> int | None:
        """How many events the console has logged so far (it keeps only the latest), or
        None when it does not answer."""
        state = self.state()
        return None if state is None else int(state["events"])

    def answers(self) -> bool:
        """Whether the server answers a good request (its state) with 200."""
        return self.state() is not None


@contextlib.contextmanager
def served_console(token: str = _TOKEN) -> Iterator[ServedConsole]:
    """Start ``homebot serve`` (symbolic apartment, as fast as possible) and stop it after."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    code = "import sys; from homebot.cli import main; sys.exit(main(sys.argv[1:]))"
    process = subprocess.Popen(
        [sys.executable, "-c", code, "serve", "--port", str(port), "--token", token,
         "--speed", "0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    served = ServedConsole(process, port, token)
    try:
        deadline = time.monotonic() + _START_TIMEOUT
        while not served.answers():
            if process.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"homebot serve did not start (exit {process.poll()})")
            time.sleep(0.1)
        yield served
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


# ---------------------------------------------------------------- one big POST


def big_post(server: ServedConsole, size: int, *, chunked: bool,
             token: str | None = None) -> dict[str, Any]:
    """POST ``size`` bytes to /api/command (with ``token``, or none) over a raw socket, as
    fast as the server takes them; the server's answer and its memory growth."""
    rss_before, peak_before = server.memory_mb()
    head = ["POST /api/command HTTP/1.1", f"Host: 127.0.0.1:{server.port}",
            "Content-Type: application/json"]
    if token is not None:
        head.append(f"X-Homebot-Token: {token}")
    head.append("Transfer-Encoding: chunked" if chunked else f"Content-Length: {size}")
    block = b'{"text": "' + b"x" * (1024 * 1024 - 12) + b'"}'
    sent = 0
    began = time.perf_counter()
    with socket.create_connection(("127.0.0.1", server.port), timeout=30) as connection:
        connection.sendall(("\r\n".join(head) + "\r\n\r\n").encode())
        try:
            while sent < size:
                piece = block[:size - sent]
                if chunked:
                    connection.sendall(f"{len(piece):x}\r\n".encode() + piece + b"\r\n")
                else:
                    connection.sendall(piece)
                sent += len(piece)
            if chunked:
                connection.sendall(b"0\r\n\r\n")
        except OSError:
            pass  # the server answered and closed the connection: the rest was never sent
        answer = _read_status(connection)
    seconds = time.perf_counter() - began
    rss_after, peak_after = server.memory_mb()
    return {"mb": round(size / 2**20), "chunked": chunked, "token": token is not None,
            "status": answer, "mb_sent_before_refusal": round(sent / 2**20, 1),
            "seconds": round(seconds, 2),
            "rss_growth_mb": round(rss_after - rss_before, 2),
            "peak_growth_mb": round(peak_after - peak_before, 2),
            "still_answers": server.answers()}


def _read_status(connection: socket.socket) -> int | None:
    received = b""
    with contextlib.suppress(OSError):
        while b"\r\n" not in received:
            piece = connection.recv(4096)
            if not piece:
                break
            received += piece
    parts = received.split(b" ", 2)
    return int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else None


# ---------------------------------------------------------------- malformed requests


@dataclass(frozen=True)
class BadRequest:
    """One malformed request: method, path (with its query), headers and body."""

    kind: str
    method: str
    path: str
    headers: dict[str, str]
    body: bytes


#: the routes a malformed request goes to (not /api/session/end: in the fuzzer's own
#: session it would end it, and every request after would only test a forgotten session)
_ROUTES = ["/api/control", "/api/drive", "/api/command", "/api/steps", "/api/resume",
           "/api/session/heartbeat", "/api/session"]
_SKILLS = ["navigate", "pick", "place", "give", "find_object", "say", "look", "follow", "guide",
           "count", "no_such_skill", ""]
_ODD_STRINGS = ["", " ", "\x00", "\x1b[31mred", "é" * 300, "x" * 5000, "kitchen", "fridge",
                "cola", "operator", "../../etc/passwd", "null", "NaN", "\udcff", "🤖" * 50]
_ODD_NUMBERS = ["1e308", "-1e308", "1e999", "NaN", "Infinity", "-Infinity", "0", "-0",
                "123456789012345678901234567890", "3.5", "-7"]


def _odd_value(rng: random.Random, depth: int = 0) -> str:
    """Some JSON text (or nearly JSON) of a seeded odd shape."""
    choice = rng.randrange(9)
    if choice == 0 or depth > 3:
        return rng.choice(_ODD_NUMBERS)
    if choice == 1:
        return json.dumps(rng.choice(_ODD_STRINGS))
    if choice == 2:
        return rng.choice(["true", "false", "null"])
    if choice == 3:
        return "[" + ", ".join(_odd_value(rng, depth + 1) for _ in range(rng.randrange(4))) + "]"
    if choice == 4:
        keys = rng.sample(["skill", "to", "object", "text", "action", "vx", "wz", "steps",
                           "type", "person", "extra", "__proto__"], rng.randrange(1, 4))
        return "{" + ", ".join(f'"{key}": {_odd_value(rng, depth + 1)}' for key in keys) + "}"
    if choice == 5:
        deep = rng.randrange(9, 3000)
        return "[" * deep + "]" * deep
    if choice == 6:
        return '{"text": "' + "y" * rng.randrange(60_000, 90_000) + '"}'
    if choice == 7:
        return "{" * rng.randrange(1, 50)  # cut short
    return json.dumps(rng.choice(_ODD_STRINGS))


def _step(rng: random.Random) -> str:
    keys = {"skill": json.dumps(rng.choice(_SKILLS))}
    for key in rng.sample(["to", "object", "placement", "person", "text", "count"],
                          rng.randrange(0, 3)):
        keys[key] = _odd_value(rng, 2)
    return "{" + ", ".join(f'"{key}": {value}' for key, value in keys.items()) + "}"


def malformed_requests(rng: random.Random, token: str, session: str,
                       kinds: Sequence[str] = KINDS) -> Iterator[BadRequest]:
    """An endless seeded stream of malformed requests to a console with ``token``, sent in
    the live session ``session`` (which may or may not hold control), of ``kinds``."""
    good = {"X-Homebot-Token": token, "X-Homebot-Session": session,
            "Content-Type": "application/json"}
    while True:
        kind = rng.choice(kinds)
        # odd_json: these as they are, an odd JSON body to a route with the right headers
        headers, method = dict(good), "POST"
        path = rng.choice(_ROUTES)
        body = _odd_value(rng).encode()
        if kind == "no_token":
            del headers["X-Homebot-Token"]
        elif kind == "wrong_token":
            headers["X-Homebot-Token"] = rng.choice([token[:-1], token + "x", "", "\x7f" * 8])
        elif kind == "no_session":
            del headers["X-Homebot-Session"]
            path = rng.choice(_ROUTES[:6])
        elif kind == "forged_session":
            headers["X-Homebot-Session"] = rng.choice([session[:-1], "operator-1", "a" * 32,
                                                       session.upper()])
            headers["X-Homebot-Operator"] = "operator-1"
            path = rng.choice([*_ROUTES, "/api/session/end"])
        elif kind == "unknown_path":
            path = rng.choice(["/api", "/api/nothing", "/admin", "/api/control/x", "//",
                               "/%00", "/api/" + "a" * 2000])
        elif kind == "wrong_method":
            method = rng.choice(["GET", "PUT", "DELETE", "PATCH"])
            path = rng.choice(_ROUTES)
        elif kind == "not_json":
            body = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 400)))
        elif kind == "control":
            path, body = "/api/control", f'{{"action": {_odd_value(rng)}}}'.encode()
        elif kind == "drive":
            path = "/api/drive"
            body = f'{{"vx": {_odd_value(rng)}, "wz": {rng.choice(_ODD_NUMBERS)}}}'.encode()
        elif kind == "command":
            path = "/api/command"
            body = f'{{"text": {_odd_value(rng)}}}'.encode()
        elif kind == "steps":
            path = "/api/steps"
            steps = ", ".join(_step(rng) for _ in range(rng.choice([0, 1, 2, 31])))
            body = f'{{"steps": [{steps}], "description": {_odd_value(rng)}}}'.encode()
        elif kind == "query":
            method, body = "GET", b""
            path = "/api/events?since=" + rng.choice(["-1", "abc", "1e9", "9" * 40, "", "%00"])
        yield BadRequest(kind, method, path, headers, body)


def fuzz(server: ServedConsole, requests: int, seed: int, kinds: Sequence[str] = KINDS, *,
         stopped: bool = False) -> dict[str, Any]:
    """Send ``requests`` malformed requests of ``kinds`` (``stopped``: with the emergency
    stop pressed first); answers by status, time and memory."""
    rng = random.Random(seed)
    session = _open_session(server, stopped=stopped)
    statuses: Counter[int] = Counter()
    faults: list[str] = []
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=30)
    rss_warm = rss_end = 0.0
    began = time.perf_counter()
    stream = malformed_requests(rng, server.token, session, kinds)
    samples: list[float] = []  # the server's resident memory at each tenth of the run
    logged: list[int | None] = []  # and the events it had logged by then
    for index in range(requests):
        if index == min(_WARM_UP, requests - 1):
            rss_warm = server.memory_mb()[0]
        if index % max(1, requests // 10) == 0:
            samples.append(round(server.memory_mb()[0], 1))
            logged.append(server.events_logged())
        request = next(stream)
        status = _send(connection, request)
        statuses[status] += 1
        if (status >= 500 or status == 0) and len(faults) < 10:
            faults.append(f"{request.kind} {request.method} {request.path[:60]} -> {status}")
    seconds = time.perf_counter() - began
    connection.close()
    rss_end = server.memory_mb()[0]
    return {"requests": requests, "seed": seed, "kinds": sorted(set(kinds)), "stopped": stopped,
            "seconds": round(seconds, 1),
            "by_status": {str(key): value for key, value in sorted(statuses.items())},
            "server_errors": sum(n for status, n in statuses.items() if status >= 500),
            "faults": faults, "rss_after_warm_up_mb": round(rss_warm, 1),
            "rss_end_mb": round(rss_end, 1), "rss_growth_mb": round(rss_end - rss_warm, 2),
            "rss_by_tenth_mb": samples, "events_logged_by_tenth": logged,
            "still_answers": server.answers()}


def _open_session(server: ServedConsole, *, stopped: bool = False) -> str:
    """A session that holds control (``stopped``: and the emergency stop pressed)."""
    connection = http.client.HTTPConnection("127.0.0.1", server.port, timeout=30)
    try:
        connection.request("POST", "/api/session", headers={"X-Homebot-Token": server.token})
        session = str(json.loads(connection.getresponse().read())["session"])
        connection.request("POST", "/api/control", body=b'{"action": "take"}',
                           headers={"X-Homebot-Token": server.token,
                                    "X-Homebot-Session": session,
                                    "Content-Type": "application/json"})
        connection.getresponse().read()
        if stopped:
            connection.request("POST", "/api/estop", headers={"X-Homebot-Token": server.token})
            pressed = connection.getresponse()
            pressed.read()
            if pressed.status != 200:
                raise RuntimeError(f"the emergency stop was answered {pressed.status}")
        return session
    finally:
        connection.close()


def _send(connection: http.client.HTTPConnection, request: BadRequest) -> int:
    """Send one request (reconnecting once where the server had closed); its status
    (0: no answer at all)."""
    for _ in range(2):
        try:
            connection.request(request.method, request.path, body=request.body or None,
                               headers=request.headers)
        except OSError:  # refused and closed before the whole body went: read the answer
            return _answer_before_close(connection)
        try:
            response = connection.getresponse()
            response.read()
        except (OSError, http.client.HTTPException):
            connection.close()
            continue
        if response.getheader("connection", "").lower() == "close":
            connection.close()
        return response.status
    return 0


def _answer_before_close(connection: http.client.HTTPConnection) -> int:
    """The status the server sent before it closed a connection we were still sending on
    (0: none could be read)."""
    sock = connection.sock
    status = 0
    if sock is not None:
        with contextlib.suppress(OSError, http.client.HTTPException):
            response = http.client.HTTPResponse(sock)
            response.begin()
            status = response.status
    connection.close()
    return status
