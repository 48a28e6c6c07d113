"""``RequestGuard``: the console's ASGI middleware that checks the token before reading a body.

FastAPI reads (and parses) a request's body before it solves the route's dependencies, so a
token check written as a dependency comes too late: an unauthenticated 300 MB POST was read
whole first. The guard sits below FastAPI, sees each request as it arrives and answers
before any ``receive()`` of the body:

- no valid token (``?token=`` or the header ``X-Homebot-Token``): 401, and the connection is
  closed (a websocket is closed with 1008 before it is accepted);
- a declared ``Content-Length`` above ``max_body``: 413 unread, and the connection closed;
- a chunked body is counted as it streams in and cut at ``max_body`` (413);
- a body nested deeper than ``max_depth`` (JSON brackets): 400 before any parser sees it,
  so no parser recurses on it.

A body that passes is handed to the app as one message; the app never reads more than
``max_body`` bytes of anyone's request.
"""

from __future__ import annotations

import json
import logging
import re
import secrets
from collections.abc import Awaitable, Callable, MutableMapping
from typing import Any
from urllib.parse import parse_qs

__all__ = ["MAX_BODY", "MAX_DEPTH", "RequestGuard", "nesting_depth"]

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

MAX_BODY = 64 * 1024  #: bytes: the largest body any console request may have
MAX_DEPTH = 8  #: the deepest nesting of JSON arrays and objects a body may have

#: a JSON string: runs of plain bytes and escapes, each taken whole (possessive). The
#: alternation ``"(?:[^"\\]|\\.)*"`` this replaces kept a backtracking frame per byte: a
#: 60 KB string took 8 MB of the regex engine's stack and up to 0.4 s, and glibc kept the
#: heap that grew for it (the served console stood 7 MB higher after the first such body).
_STRINGS = re.compile(rb'"[^"\\]*+(?:\\.[^"\\]*+)*+"', re.DOTALL)
_log = logging.getLogger("homebot.web")


def nesting_depth(body: bytes) -> int:
    """How deeply the JSON arrays and objects of ``body`` nest (brackets inside strings do
    not count); read in one pass, without recursion, whatever the input."""
    if body.count(b"[") + body.count(b"{") == 0:
        return 0
    bare = _STRINGS.sub(b'""', body)
    depth = deepest = 0
    for byte in bare:
        if byte in b"[{":
            depth += 1
            deepest = max(deepest, depth)
        elif byte in b"]}":
            depth = max(0, depth - 1)
    return deepest


class RequestGuard:
    """Refuse what has no token, or too big or too deep a body, before the app reads it."""

    def __init__(self, app: ASGIApp, *, token: str, max_body: int = MAX_BODY,
                 max_depth: int = MAX_DEPTH, counts: dict[str, int] | None = None) -> None:
        self.app = app
        self._token = token.encode()
        self.max_body = max_body
        self.max_depth = max_depth
        #: refusals by kind (``unauthorised``, ``too_large``, ``too_deep``), for the figures
        self.counts = counts if counts is not None else {}

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        if not self._authorised(scope):
            self._count("unauthorised", scope)
            if scope["type"] == "websocket":
                await send({"type": "websocket.close", "code": 1008,
                            "reason": "a valid token is required"})
            else:
                await _refuse(send, 401, "a valid token is required (?token=... or the header "
                                         "X-Homebot-Token)")
            return
        if scope["type"] == "websocket":
            await self.app(scope, receive, send)
            return
        declared = _header(scope, b"content-length")
        if declared is not None and (not declared.isdigit() or int(declared) > self.max_body):
            self._count("too_large", scope)
            await _refuse(send, 413, f"a request body may have at most {self.max_body} bytes")
            return
        body = bytearray()
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            body += message.get("body", b"")
            if len(body) > self.max_body:  # a chunked body: cut where it passes the cap
                self._count("too_large", scope)
                await _refuse(send, 413, f"a request body may have at most {self.max_body} "
                                         "bytes")
                return
            if not message.get("more_body", False):
                break
        if nesting_depth(bytes(body)) > self.max_depth:
            self._count("too_deep", scope)
            await _refuse(send, 400, f"the JSON body nests deeper than {self.max_depth} levels")
            return
        await self.app(scope, _replay(bytes(body), receive), send)

    def _authorised(self, scope: Scope) -> bool:
        given = _header(scope, b"x-homebot-token")
        if given is None:
            query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
            given = (query.get("token") or [""])[0]
        return secrets.compare_digest(given.encode("utf-8", "replace"), self._token)

    def _count(self, kind: str, scope: Scope) -> None:
        self.counts[kind] = self.counts.get(kind, 0) + 1
        client = scope.get("client") or ("?", 0)
        _log.warning("refused %s %r from %s: %s", scope.get("method", "WS"),
                     scope.get("path", "")[:80], client[0], kind)


def _header(scope: Scope, name: bytes) -> str | None:
    for key, value in scope.get("headers", []):
        if key.lower() == name:
            return bytes(value).decode("latin-1").strip()
    return None


async def _refuse(send: Send, status: int, error: str) -> None:
    """Answer ``status`` with a one-line JSON error and close the connection after it, so
    the rest of a refused body is never read into the server."""
    body = json.dumps({"error": error}).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode()),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})


def _replay(body: bytes, receive: Receive) -> Receive:
    """The app's ``receive``: the body read by the guard, then the client's own messages."""
    sent = False

    async def replayed() -> Message:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replayed
