"""A few hundred malformed requests to the console app in-process: each answered, none a fault.

The same seeded generator as ``homebot bench console_fuzz`` (which sends 10 000 to a served
console over loopback and reads its memory), here through the ASGI app in-process (Starlette's
test client: every layer from the guard down, no sockets), so it runs in seconds.
"""

from __future__ import annotations

import random
from collections import Counter

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient

from homebot.bench.console_fuzz import KINDS, malformed_requests
from homebot.web import ConsoleSettings
from homebot.web.app import create_app
from homebot.world import World

TOKEN = "fuzz-test-token"


@pytest.mark.parametrize("seed", [1, 2])
def test_malformed_requests_are_answered_with_one_line_errors_and_the_console_goes_on(
        seed: int) -> None:
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0)
    app = create_app(settings)
    with TestClient(app) as client:  # a server fault would be raised here, not answered
        page = {"X-Homebot-Token": TOKEN}
        session = client.post("/api/session", headers=page).json()["session"]
        page["X-Homebot-Session"] = session
        assert client.post("/api/control", json={"action": "take"}, headers=page).is_success
        statuses: Counter[int] = Counter()
        stream = malformed_requests(random.Random(seed), TOKEN, session)
        for _ in range(300):
            request = next(stream)
            response = client.request(request.method, request.path, content=request.body,
                                       headers=request.headers)
            statuses[response.status_code] += 1
            assert response.status_code < 500, request
            if response.status_code >= 400:
                error = response.json()["error"]
                assert error and "\n" not in error and "Traceback" not in error, request
        home = app.state.console
        assert home._worker is not None and home._worker.is_alive()
        assert home.wait_idle(60.0)
        assert client.get("/api/state", headers={"X-Homebot-Token": TOKEN}).status_code == 200
        assert len(app.state.sessions) <= app.state.sessions.limit
    # the stream reached every kind of refusal
    assert {401, 403, 404, 405, 413, 422} <= set(statuses), statuses
    assert app.state.refused["unauthorised"] == statuses[401]


@pytest.mark.parametrize("kind", sorted(set(KINDS)))
def test_the_generator_sends_one_kind_alone_when_asked(kind: str) -> None:
    """``--only KIND``: every request is of that kind, and each kind is its own shape."""
    stream = malformed_requests(random.Random(3), TOKEN, "s", (kind,))
    requests = [next(stream) for _ in range(60)]
    assert {request.kind for request in requests} == {kind}
    with_token = [request for request in requests
                  if request.headers.get("X-Homebot-Token") == TOKEN]
    if kind == "query":
        assert {request.method for request in requests} == {"GET"}
        assert all(request.path.startswith("/api/events?since=") for request in requests)
    elif kind == "odd_json":  # an odd body to a known route, with the token and the session
        assert len(with_token) == len(requests)
        assert {request.method for request in requests} == {"POST"}
        assert all(request.body and request.path.startswith("/api/") for request in requests)
    elif kind == "no_token":
        assert not with_token
