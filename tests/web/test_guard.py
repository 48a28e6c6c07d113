"""The guard refuses before reading: no token, a body over the cap or nested too deep.

In-process, the ASGI app's ``receive`` is watched: a refused request's body is never asked
for. Over loopback, ``homebot serve`` runs in a process of its own, and unauthenticated
100 MB POSTs (declared, and chunked) must cost it under 5 MB of resident memory.
"""

from __future__ import annotations

import asyncio
import json
import tracemalloc
from collections.abc import MutableMapping
from typing import Any

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")

from homebot.bench.console_fuzz import big_post, served_console
from homebot.web.guard import MAX_BODY, MAX_DEPTH, RequestGuard, nesting_depth

TOKEN = "guard-test-token"
Message = MutableMapping[str, Any]


class Endpoint:
    """The app below the guard: it reads the whole body and answers 200 with its length."""

    def __init__(self) -> None:
        self.calls = 0

    async def __call__(self, scope: Message, receive: Any, send: Any) -> None:
        self.calls += 1
        body = b""
        while True:
            message = await receive()
            body += message.get("body", b"")
            if not message.get("more_body"):
                break
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": str(len(body)).encode()})


def _call(guard: RequestGuard, headers: dict[str, str], chunks: list[bytes],
          query: str = "") -> tuple[int, dict[str, Any], int]:
    """One POST through ``guard``: (status, JSON answer or {}, chunks the guard asked for)."""
    asked = 0
    sent: list[Message] = []

    async def receive() -> Message:
        nonlocal asked
        asked += 1
        if asked > len(chunks):
            return {"type": "http.disconnect"}
        return {"type": "http.request", "body": chunks[asked - 1],
                "more_body": asked < len(chunks)}

    async def send(message: Message) -> None:
        sent.append(message)

    scope = {"type": "http", "method": "POST", "path": "/api/command",
             "query_string": query.encode(), "client": ("127.0.0.1", 5),
             "headers": [(k.lower().encode(), v.encode()) for k, v in headers.items()]}
    asyncio.run(guard(scope, receive, send))
    start = next(m for m in sent if m["type"] == "http.response.start")
    body = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    answer = json.loads(body) if start["status"] != 200 else {}
    if start["status"] != 200:
        assert (b"connection", b"close") in start["headers"]  # the rest is never read
    return start["status"], answer, asked


@pytest.mark.parametrize("headers", [{}, {"X-Homebot-Token": "wrong"},
                                     {"X-Homebot-Token": TOKEN[:-1]},
                                     {"Content-Length": "300000000"}])
def test_without_the_token_the_body_is_never_read(headers: dict[str, str]) -> None:
    endpoint = Endpoint()
    guard = RequestGuard(endpoint, token=TOKEN)
    status, answer, asked = _call(guard, headers, [b"x" * 1024] * 1000)
    assert (status, asked, endpoint.calls) == (401, 0, 0)
    assert "token" in answer["error"]
    assert guard.counts == {"unauthorised": 1}


def test_the_token_in_the_query_or_the_header_lets_a_small_body_through() -> None:
    endpoint = Endpoint()
    guard = RequestGuard(endpoint, token=TOKEN)
    assert _call(guard, {"X-Homebot-Token": TOKEN}, [b'{"text": "hi"}'])[0] == 200
    assert _call(guard, {}, [b'{"a": ', b'"b"}'], query=f"token={TOKEN}")[0] == 200
    assert endpoint.calls == 2


def test_a_declared_length_over_the_cap_is_refused_unread() -> None:
    endpoint = Endpoint()
    guard = RequestGuard(endpoint, token=TOKEN)
    for declared in (str(MAX_BODY + 1), "300000000", "-5", "12abc"):
        status, answer, asked = _call(guard, {"X-Homebot-Token": TOKEN,
                                              "Content-Length": declared}, [b"x"])
        assert (status, asked) == (413, 0), declared
    assert str(MAX_BODY) in answer["error"] and endpoint.calls == 0


def test_a_chunked_body_is_cut_where_it_passes_the_cap() -> None:
    endpoint = Endpoint()
    guard = RequestGuard(endpoint, token=TOKEN)
    chunk = 8 * 1024
    status, _, asked = _call(guard, {"X-Homebot-Token": TOKEN}, [b"x" * chunk] * 10_000)
    assert status == 413 and asked == MAX_BODY // chunk + 1 and endpoint.calls == 0
    # just under the cap, in pieces, passes whole
    pieces = [b"y" * chunk] * (MAX_BODY // chunk)
    assert _call(guard, {"X-Homebot-Token": TOKEN}, pieces)[0] == 200


def test_a_body_nested_too_deep_is_refused_before_any_parser_sees_it() -> None:
    endpoint = Endpoint()
    guard = RequestGuard(endpoint, token=TOKEN)
    deep = b'{"steps": ' + b"[" * 20_000 + b"]" * 20_000 + b"}"
    status, answer, _ = _call(guard, {"X-Homebot-Token": TOKEN}, [deep])
    assert status == 400 and f"deeper than {MAX_DEPTH}" in answer["error"]
    assert endpoint.calls == 0


def test_nesting_depth_counts_brackets_outside_strings_only() -> None:
    assert nesting_depth(b'{"a": [1, {"b": [2]}]}') == 4
    assert nesting_depth(b'{"text": "[[[[[[[[[[[[ {{{{ \\" [[["}') == 1
    assert nesting_depth(b"[" * 100_000) == 100_000
    assert nesting_depth(b"not json at all") == 0
    assert nesting_depth(b'["a\\\\", ["b"]]') == 2  # an escaped backslash ends no string early
    assert nesting_depth(b'["\\"]", [[') == 3  # an escaped quote does not end it
    assert nesting_depth(b'[["never closed [[[[') == 6  # an unclosed quote opens no string


@pytest.mark.parametrize("text", [b"y" * 60_000, b"ab\\n" * 20_000, b"\\u00e9" * 10_000])
def test_nesting_depth_reads_a_long_string_in_little_memory(text: bytes) -> None:
    """A body under the cap that is one long string costs the guard no more than a few
    times its size: the regex engine keeps no frame per byte (it took 8 MB for 60 KB, and
    the heap it grew stayed with the server)."""
    body = b'{"text": "' + text + b'"}'
    tracemalloc.start()
    try:
        depth = nesting_depth(body)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert depth == 1
    assert peak < 4 * len(body)


def test_unauthenticated_100_mb_posts_cost_the_served_console_under_5_mb() -> None:
    """A real ``homebot serve`` process on loopback; its own resident memory."""
    with served_console(TOKEN) as server:
        size = 100 * 1024 * 1024
        for chunked in (False, True):
            figures = big_post(server, size, chunked=chunked)
            assert figures["status"] == 401, figures
            assert figures["rss_growth_mb"] < 5.0 and figures["peak_growth_mb"] < 5.0, figures
        over = big_post(server, size, chunked=False, token=TOKEN)
        assert over["status"] == 413 and over["peak_growth_mb"] < 5.0, over
        assert server.answers()
