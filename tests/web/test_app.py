"""The console's API and websocket in-process: access, sessions and the control lease, a full
run, stop, help."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("httpx")

from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from homebot.web import Console, ConsoleSettings
from homebot.web.app import create_app
from homebot.world import World

TOKEN = "test-token-123"
LEASE = 10.0
_WAIT = 120.0  # wall seconds at most for a task in a test (it takes well under one)


class SteppedClock:
    """The sessions' and the lease's clock: it moves only when a test moves it."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def clock() -> SteppedClock:
    return SteppedClock()


@pytest.fixture
def client(clock: SteppedClock) -> Iterator[TestClient]:
    settings = ConsoleSettings(world=World.load("apartment"), token=TOKEN, speed=0.0,
                               lease=LEASE)
    with TestClient(create_app(settings, clock=clock)) as test_client:
        yield test_client


def _operator(client: TestClient) -> dict[str, str]:
    """A page's headers: the token and a session the server issued."""
    opened = client.post("/api/session", headers={"X-Homebot-Token": TOKEN})
    assert opened.status_code == 200
    return {"X-Homebot-Token": TOKEN, "X-Homebot-Session": opened.json()["session"],
            "name": opened.json()["operator"]}


def _headers(page: dict[str, str]) -> dict[str, str]:
    return {key: value for key, value in page.items() if key != "name"}


@pytest.fixture
def ann(client: TestClient) -> dict[str, str]:
    return _operator(client)


@pytest.fixture
def bob(client: TestClient) -> dict[str, str]:
    return _operator(client)


def _console(client: TestClient) -> Console:
    home: Console = client.app.state.console  # type: ignore[attr-defined]
    return home


ROUTES = [("get", "/", None), ("get", "/api/map", None), ("get", "/api/state", None),
          ("get", "/api/camera.jpg", None),
          ("get", "/api/events", None), ("post", "/api/session", {}),
          ("post", "/api/session/heartbeat", {}), ("post", "/api/session/end", {}),
          ("post", "/api/control", {"action": "take"}),
          ("post", "/api/estop", {}), ("post", "/api/estop/release", {}),
          ("post", "/api/drive", {"vx": 0.1}), ("post", "/api/command", {"text": "hi"}),
          ("post", "/api/steps", {"steps": [{"skill": "say", "text": "hi"}]}),
          ("post", "/api/resume", {})]


@pytest.mark.parametrize(("method", "path", "body"), ROUTES)
def test_every_request_without_the_token_is_refused(client: TestClient, method: str,
                                                    path: str, body: Any) -> None:
    for headers in ({"X-Homebot-Operator": "ann"},
                    {"X-Homebot-Token": "wrong-token", "X-Homebot-Operator": "ann"}):
        response = client.request(method, path, json=body, headers=headers)
        assert response.status_code == 401
        assert "token" in response.json()["error"]
    assert _console(client).estop is False  # nothing got through
    assert _console(client).controller is None
    assert len(client.app.state.sessions) == 0  # type: ignore[attr-defined]


def test_the_websocket_without_the_token_is_refused(client: TestClient) -> None:
    for url in ("/ws", "/ws?token=wrong"):
        with pytest.raises(WebSocketDisconnect) as refused, client.websocket_connect(url) as ws:
            ws.receive_json()
        assert refused.value.code == 1008


def test_the_page_loads_with_the_token(client: TestClient) -> None:
    page = client.get(f"/?token={TOKEN}")
    assert page.status_code == 200
    assert "EMERGENCY STOP" in page.text and "function connect()" in page.text


def test_a_second_operator_cannot_act_as_the_first_whatever_headers_it_sends(
        client: TestClient, ann: dict[str, str], bob: dict[str, str]) -> None:
    home = _console(client)
    ANN, BOB = _headers(ann), _headers(bob)
    assert client.post("/api/control", json={"action": "take"}, headers=ANN).status_code == 200
    assert home.controller == ann["name"]
    taken = client.post("/api/control", json={"action": "take"}, headers=BOB)
    assert taken.status_code == 409 and "another operator" in taken.json()["error"]
    # bob names ann every way a client can: the old operator header, her public name as a
    # session, a session id of his own making; none of them is ann's session
    for posing in ({**BOB, "X-Homebot-Operator": ann["name"]},
                   {"X-Homebot-Token": TOKEN, "X-Homebot-Operator": ann["name"]},
                   {"X-Homebot-Token": TOKEN, "X-Homebot-Session": ann["name"]},
                   {"X-Homebot-Token": TOKEN, "X-Homebot-Session": "ann"}):
        for path, body in (("/api/command", {"text": "go to the kitchen"}),
                           ("/api/control", {"action": "release"}),
                           ("/api/estop/release", {}), ("/api/resume", {})):
            refused = client.post(path, json=body, headers=posing)
            assert refused.status_code in (403, 409), (posing, path)
        assert home.controller == ann["name"]
    assert client.post("/api/estop", headers=BOB).status_code == 200  # anyone may stop
    assert client.post("/api/estop/release", headers=BOB).status_code == 409
    assert home.estop
    assert client.post("/api/estop/release", headers=ANN).status_code == 200
    client.post("/api/control", json={"action": "release"}, headers=ANN)
    assert client.post("/api/control", json={"action": "take"}, headers=BOB).status_code == 200
    assert home.controller == bob["name"]


def test_control_lapses_when_the_page_stops_renewing_it(
        client: TestClient, clock: SteppedClock, ann: dict[str, str],
        bob: dict[str, str]) -> None:
    home = _console(client)
    ANN, BOB = _headers(ann), _headers(bob)
    assert client.post("/api/control", json={"action": "take"}, headers=ANN).status_code == 200
    for _ in range(5):  # the page's heartbeat holds it well past one lease
        clock.now += 0.8 * LEASE
        beat = client.post("/api/session/heartbeat", headers=ANN).json()
        assert beat["controller"] == ann["name"] and beat["lease_left"] == LEASE
    assert client.post("/api/control", json={"action": "take"}, headers=BOB).status_code == 409
    clock.now += LEASE + 0.001  # the page went away (crashed, network lost): no heartbeat
    assert home.controller is None
    assert client.get("/api/state", headers=BOB).json()["controller"] is None
    refused = client.post("/api/command", json={"text": "go to the kitchen"}, headers=ANN)
    assert refused.status_code == 409 and "take control" in refused.json()["error"]
    assert client.post("/api/control", json={"action": "take"}, headers=BOB).status_code == 200
    assert home.controller == bob["name"]
    # a late heartbeat from the page that lost it takes nothing back
    assert client.post("/api/session/heartbeat", headers=ANN).json()["controller"] == bob["name"]


def test_a_page_that_goes_away_gives_control_back_at_once(
        client: TestClient, ann: dict[str, str], bob: dict[str, str]) -> None:
    home = _console(client)
    assert client.post("/api/control", json={"action": "take"},
                       headers=_headers(ann)).status_code == 200
    # pagehide's beacon: no custom headers, the token and the session in the query
    gone = client.post(f"/api/session/end?token={TOKEN}&session={ann['X-Homebot-Session']}")
    assert gone.status_code == 200 and gone.json()["controller"] is None
    assert home.controller is None
    # the ended session is gone: nothing more in its name
    again = client.post("/api/control", json={"action": "take"}, headers=_headers(ann))
    assert again.status_code == 403 and "POST /api/session" in again.json()["error"]
    assert client.post("/api/control", json={"action": "take"},
                       headers=_headers(bob)).status_code == 200


def test_a_fetch_command_completes_with_the_map_log_speech_and_steps_live(
        client: TestClient, ann: dict[str, str]) -> None:
    home = _console(client)
    ANN = _headers(ann)
    client.post("/api/control", json={"action": "take"}, headers=ANN)
    with client.websocket_connect(f"/ws?token={TOKEN}") as ws:
        assert ws.receive_json()["type"] == "map"
        sent = client.post("/api/command", json={"text": "bring me the cola from the fridge"},
                           headers=ANN)
        assert sent.status_code == 200
        assert home.wait_idle(_WAIT)
        kinds: set[str] = set()
        statuses: set[str] = set()
        positions: set[tuple[float, float]] = set()
        for _ in range(400):
            message = ws.receive_json()
            if message["type"] == "events":
                kinds.update(event["kind"] for event in message["events"])
                continue
            positions.add(tuple(message["robot"][:2]))
            statuses.update(step["status"] for step in message["task"]["steps"])
            if message["task"]["ended"] is not None and not message["busy"]:
                break
    assert message["task"]["ended"] is True
    assert [step["skill"] for step in message["task"]["steps"]][-1] == "give"
    assert statuses >= {"verified"}
    assert "I have done what you asked." in message["speech"]
    assert {"task.start", "skill.start", "skill.status", "speech", "task.end"} <= kinds
    with home.lock:  # ground truth: the operator holds the cola
        assert home.sim.object_location["cola"] == f"person:{home.world.model.operator}"
    assert message["objects"]["cola"]["at"].startswith("person:")


def test_the_stop_preempts_a_running_task_and_the_operator_helps_it_on(
        client: TestClient, ann: dict[str, str], bob: dict[str, str]) -> None:
    home = _console(client)
    ANN, BOB = _headers(ann), _headers(bob)
    client.post("/api/control", json={"action": "take"}, headers=ANN)
    steps = [{"skill": "pick", "object": "cola"}, {"skill": "pick", "object": "milk"},
             {"skill": "pick", "object": "water"}]
    assert client.post("/api/steps", json={"steps": steps}, headers=ANN).status_code == 200
    assert home.wait_idle(_WAIT)
    state = client.get("/api/state", headers=ANN).json()
    assert [step["status"] for step in state["task"]["steps"]][:2] == ["verified", "verified"]
    assert state["task"]["ended"] is False and state["help"]["skill"] == "pick"
    assert state["help"]["levels"] == ["skill"]  # symbolic: no body to drive
    # the operator steps down a level: puts the milk away, then lets the task go on
    place = [{"skill": "place", "placement": "kitchen counter", "object": "milk"}]
    assert client.post("/api/steps", json={"steps": place}, headers=ANN).status_code == 200
    assert home.wait_idle(_WAIT)
    assert client.post("/api/resume", headers=ANN).status_code == 200
    assert home.wait_idle(_WAIT)
    with home.lock:
        assert set(home.sim.hands.values()) == {"cola", "water"}
    # and a stop pressed while the robot drives preempts it where it is
    go = [{"skill": "navigate", "to": "bedroom"}]
    home.settings.speed = 0.2  # slower than real time: the drive outlasts a loaded machine
    assert client.post("/api/steps", json={"steps": go}, headers=ANN).status_code == 200
    with home.lock:
        home.lock.wait_for(lambda: home.steps.current >= 0 and
                           home.steps.steps[home.steps.current]["status"] == "running", _WAIT)
    assert client.post("/api/estop", headers=BOB).status_code == 200
    assert home.wait_idle(_WAIT)
    with home.lock:
        assert home.world.room_at(*home.sim.robot_pose[:2]) != "bedroom"
        assert any(True for _ in home.sim.events.of_kind("console.preempted"))
    assert client.post("/api/command", json={"text": "go to the bedroom"},
                       headers=ANN).status_code == 409  # stopped until released
    # the step view tells the truth: the task ended, stopped, and nothing is still running
    with home.lock:
        ended = list(home.sim.events.of_kind("task.end"))[-1]
        pressed = next(home.sim.events.of_kind("console.estop"))
        assert ended.data == {"success": False, "reason": "emergency stop"}
        assert ended.time >= pressed.time
    state = client.get("/api/state", headers=ANN).json()
    assert state["task"]["ended"] is False and state["task"]["outcome"] == "stopped"
    assert [step["status"] for step in state["task"]["steps"]] == ["stopped"]
    assert state["help"]["stopped"] and state["help"]["step"] == 0 and not state["busy"]
    # and the task goes on once the stop is released
    assert client.post("/api/resume", headers=ANN).status_code == 409  # not while stopped
    assert client.post("/api/estop/release", headers=ANN).status_code == 200
    home.settings.speed = 0.0
    resumed = client.post("/api/resume", headers=ANN)
    assert resumed.status_code == 200 and resumed.json()["queued"] == go
    assert home.wait_idle(_WAIT)
    state = client.get("/api/state", headers=ANN).json()
    assert state["task"]["outcome"] == "done"
    assert [step["status"] for step in state["task"]["steps"]] == ["verified"]
    with home.lock:  # ground truth: it got there
        assert home.world.room_at(*home.sim.robot_pose[:2]) == "bedroom"
