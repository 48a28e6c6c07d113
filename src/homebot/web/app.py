"""``create_app``: the console's FastAPI app: the page, a JSON API and a live websocket.

Access: every HTTP request and websocket carries the token (``?token=`` or the header
``X-Homebot-Token``); without it the request is refused (401; the websocket is closed with
1008 before it is accepted). Commands also name the operator (``X-Homebot-Operator``); only
the operator holding control can command the robot, everyone with the token can watch and
press the emergency stop.

Back-pressure (the websocket): the server samples the home ``rate`` times a (wall) second.
Each watcher has a slot for the latest state and a bounded queue of events: a state not yet
sent when the next one comes is replaced by it (latest state wins, counted as superseded);
events go out in order, and when a watcher falls more than ``EVENT_QUEUE`` events behind the
oldest are dropped and it is told how many (``lost``).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import secrets
import time
from collections import deque
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from importlib import resources
from typing import Any

from fastapi import Depends, FastAPI, Header, Query, Request, WebSocket, WebSocketDisconnect
from fastapi.responses import HTMLResponse, JSONResponse
from pydantic import BaseModel, Field

from homebot.errors import ConsoleError, HomebotError
from homebot.web.console import Console, ConsoleSettings, static_map

__all__ = ["EVENT_QUEUE", "Watcher", "create_app"]

EVENT_QUEUE = 500


class ControlRequest(BaseModel):
    type: str = "control"
    action: str = Field(pattern="^(take|release)$")


class DriveRequest(BaseModel):
    type: str = "drive"
    vx: float = 0.0
    wz: float = 0.0


class CommandRequest(BaseModel):
    type: str = "command"
    text: str = Field(max_length=500)


class StepsRequest(BaseModel):
    type: str = "steps"
    steps: list[dict[str, Any]] = Field(max_length=30)
    description: str = ""


@dataclass(eq=False)
class Watcher:
    """One websocket's outgoing slot (latest state) and bounded event queue."""

    state: str | None = None
    events: deque[dict[str, Any]] = field(default_factory=lambda: deque(maxlen=EVENT_QUEUE))
    wake: asyncio.Event = field(default_factory=asyncio.Event)
    superseded: int = 0
    lost: int = 0

    def offer(self, state: str, events: list[dict[str, Any]]) -> None:
        if self.state is not None:
            self.superseded += 1
        self.state = state
        overflow = len(self.events) + len(events) - EVENT_QUEUE
        if overflow > 0:
            self.lost += overflow
        self.events.extend(events)
        self.wake.set()


def create_app(settings: ConsoleSettings, *, rate: float = 10.0,
               console: Console | None = None) -> FastAPI:
    """The console app over a new home (or ``console``), sampled ``rate`` times a second."""
    home = console or Console(settings)
    watchers: set[Watcher] = set()
    token = settings.token

    async def broadcast() -> None:
        seq, seen = 0, home.event_count
        loop = asyncio.get_running_loop()
        due = loop.time()
        while True:
            state = await asyncio.to_thread(home.snapshot)
            events = await asyncio.to_thread(home.events_since, seen)
            if events:
                seen = events[-1]["n"]
            seq += 1
            state["seq"] = seq
            state["sent"] = time.time()
            text = json.dumps(state, ensure_ascii=False)
            for watcher in list(watchers):
                watcher.offer(text, events)
            # the server's sampling period, in wall time, on a fixed cadence (not drifting)
            due = max(due + 1.0 / rate, loop.time() - 1.0 / rate)
            await asyncio.sleep(max(0.0, due - loop.time()))

    @contextlib.asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        home.start()
        sampler = asyncio.create_task(broadcast())
        try:
            yield
        finally:
            sampler.cancel()
            home.close()

    app = FastAPI(title="homebot console", lifespan=lifespan, docs_url=None, redoc_url=None,
                  openapi_url=None)
    app.state.console = home
    app.state.watchers = watchers
    app.state.stats = {"superseded": 0, "lost_events": 0, "watchers": 0}

    def authorised(query: str | None = Query(None, alias="token"),
                   header: str | None = Header(None, alias="X-Homebot-Token")) -> None:
        given = query or header or ""
        if not secrets.compare_digest(given.encode(), token.encode()):
            raise _Refused

    def operator(name: str | None = Header(None, alias="X-Homebot-Operator")) -> str:
        if not name:
            raise ConsoleError("name the operator (header X-Homebot-Operator)")
        return name

    @app.exception_handler(_Refused)
    async def refused(request: Request, error: _Refused) -> JSONResponse:
        return JSONResponse({"error": "a valid token is required (?token=...)"}, status_code=401)

    @app.exception_handler(ConsoleError)
    async def conflict(request: Request, error: ConsoleError) -> JSONResponse:
        return JSONResponse({"error": str(error)}, status_code=409)

    @app.exception_handler(HomebotError)
    async def bad(request: Request, error: HomebotError) -> JSONResponse:
        return JSONResponse({"error": str(error)}, status_code=400)

    guarded = [Depends(authorised)]

    @app.get("/", response_class=HTMLResponse, dependencies=guarded)
    def page() -> str:
        folder = resources.files("homebot.web") / "static"
        html = (folder / "index.html").read_text(encoding="utf-8")
        script = (folder / "console.js").read_text(encoding="utf-8")
        return html.replace("/*CONSOLE_JS*/", script)

    @app.get("/api/map", dependencies=guarded)
    def map_() -> dict[str, Any]:
        return static_map(home.world)

    @app.get("/api/state", dependencies=guarded)
    def state() -> dict[str, Any]:
        return home.snapshot()

    @app.get("/api/events", dependencies=guarded)
    def events(since: int = 0) -> list[dict[str, Any]]:
        return home.events_since(since)

    @app.post("/api/control", dependencies=guarded)
    def control(body: ControlRequest, who: str = Depends(operator)) -> dict[str, Any]:
        if body.action == "take":
            home.take_control(who)
        else:
            home.release_control(who)
        return {"controller": home.controller}

    @app.post("/api/estop", dependencies=guarded)
    def estop() -> dict[str, Any]:
        home.emergency_stop()
        return {"estop": True}

    @app.post("/api/estop/release", dependencies=guarded)
    def release(who: str = Depends(operator)) -> dict[str, Any]:
        home.release_stop(who)
        return {"estop": False}

    @app.post("/api/drive", dependencies=guarded)
    def drive(body: DriveRequest, who: str = Depends(operator)) -> dict[str, Any]:
        twist = home.drive(who, body.vx, body.wz)
        return {"vx": twist.vx, "wz": twist.wz}

    @app.post("/api/command", dependencies=guarded)
    def command(body: CommandRequest, who: str = Depends(operator)) -> dict[str, Any]:
        home.command(who, body.text)
        return {"queued": body.text}

    @app.post("/api/steps", dependencies=guarded)
    def steps(body: StepsRequest, who: str = Depends(operator)) -> dict[str, Any]:
        task = home.run_steps(who, body.steps, body.description)
        return {"queued": task.to_dicts()}

    @app.post("/api/resume", dependencies=guarded)
    def resume(who: str = Depends(operator)) -> dict[str, Any]:
        return {"queued": home.resume(who).to_dicts()}

    @app.websocket("/ws")
    async def live(socket: WebSocket) -> None:
        given = socket.query_params.get("token") or socket.headers.get("x-homebot-token") or ""
        if not secrets.compare_digest(given.encode(), token.encode()):
            await socket.close(code=1008)
            return
        await socket.accept()
        watcher = Watcher()
        watchers.add(watcher)
        try:
            await socket.send_text(json.dumps(static_map(home.world)))
            reported = 0
            while True:
                await watcher.wake.wait()
                watcher.wake.clear()
                if watcher.events or watcher.lost != reported:
                    batch = list(watcher.events)
                    watcher.events.clear()
                    await socket.send_text(json.dumps(
                        {"type": "events", "events": batch, "lost": watcher.lost - reported},
                        ensure_ascii=False))
                    reported = watcher.lost
                text, watcher.state = watcher.state, None
                if text is not None:
                    await socket.send_text(text)
        except (WebSocketDisconnect, RuntimeError):
            pass
        finally:
            watchers.discard(watcher)
            stats = app.state.stats
            stats["superseded"] += watcher.superseded
            stats["lost_events"] += watcher.lost
            stats["watchers"] += 1

    return app


class _Refused(Exception):
    """No valid token: answered with 401."""
