"""``create_app``: the console's FastAPI app: the page, a JSON API and a live websocket.

Access: every HTTP request and websocket carries the token (``?token=`` or the header
``X-Homebot-Token``). ``RequestGuard`` checks it before anything reads the body, and caps
bodies (``homebot.web.guard``); every body is then one of the ``homebot.web.messages``
models. An operator is a session the server issued (``POST /api/session``), sent back as
``X-Homebot-Session``; control is a lease bound to it that the page renews with a heartbeat
and gives back when it goes away (``homebot.web.sessions``). Only the operator holding
control can command the robot; everyone with the token can watch and press the emergency
stop. A bad request is answered with a one-line error (401, 403, 409, 413, 422) and logged.

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
import logging
import time
from collections import deque
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass, field
from importlib import resources
from typing import Any

from fastapi import Depends, FastAPI, Header, Query, Request, WebSocket, WebSocketDisconnect
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException

from homebot.errors import ConsoleError, HomebotError
from homebot.web.console import Console, ConsoleSettings, static_map
from homebot.web.guard import RequestGuard
from homebot.web.messages import (
    CommandRequest,
    ControlRequest,
    DriveRequest,
    StepsRequest,
    first_problem,
)
from homebot.web.sessions import Sessions

__all__ = ["EVENT_QUEUE", "Watcher", "create_app"]

EVENT_QUEUE = 500
_log = logging.getLogger("homebot.web")


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
               console: Console | None = None,
               clock: Callable[[], float] = time.monotonic) -> FastAPI:
    """The console app over a new home (or ``console``), sampled ``rate`` times a second;
    sessions (and a new home's control lease) read ``clock`` (wall seconds)."""
    home = console or Console(settings, lease_clock=clock)
    watchers: set[Watcher] = set()

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
    refused: dict[str, int] = {}  # the guard's refusals and the rejected bodies, by kind
    app.state.refused = refused
    app.state.sessions = sessions = Sessions(clock=clock)
    # below Starlette's error handler, above everything else: nothing below it (FastAPI's
    # body parsing included) runs for a refused request
    app.add_middleware(RequestGuard, token=settings.token, counts=refused)

    def operator(header: str | None = Header(None, alias="X-Homebot-Session"),
                 query: str | None = Query(None, alias="session", max_length=64)) -> str:
        name = sessions.name(header or query)
        if name is None:
            raise _NoSession
        return name

    def _bad(kind: str, request: Request, error: str, status: int) -> JSONResponse:
        refused[kind] = refused.get(kind, 0) + 1
        # repr: what a client typed reaches the log escaped, one line, bounded
        _log.warning("%s %r answered %d: %r", request.method, request.url.path[:80], status,
                     error[:300])
        return JSONResponse({"error": error}, status_code=status)

    @app.exception_handler(_NoSession)
    async def no_session(request: Request, error: _NoSession) -> JSONResponse:
        return _bad("no_session", request, "no such session: start one with POST /api/session "
                    "(the page does when it loads), then send its id as X-Homebot-Session", 403)

    @app.exception_handler(StarletteHTTPException)
    async def http_error(request: Request, error: StarletteHTTPException) -> JSONResponse:
        return _bad("http", request, f"{error.detail}: {request.method} "
                    f"{request.url.path[:80]}", error.status_code)

    @app.exception_handler(RequestValidationError)
    async def invalid(request: Request, error: RequestValidationError) -> JSONResponse:
        return _bad("invalid", request, first_problem(error.errors()), 422)

    @app.exception_handler(ConsoleError)
    async def conflict(request: Request, error: ConsoleError) -> JSONResponse:
        return _bad("conflict", request, str(error), 409)

    @app.exception_handler(HomebotError)
    async def bad(request: Request, error: HomebotError) -> JSONResponse:
        return _bad("bad", request, str(error), 400)

    @app.get("/", response_class=HTMLResponse)
    def page() -> str:
        folder = resources.files("homebot.web") / "static"
        html = (folder / "index.html").read_text(encoding="utf-8")
        script = (folder / "console.js").read_text(encoding="utf-8")
        return html.replace("/*CONSOLE_JS*/", script)

    @app.get("/api/map")
    def map_() -> dict[str, Any]:
        return static_map(home.world)

    @app.get("/api/camera.jpg")
    def camera(request: Request) -> Response:
        try:
            stamp, jpeg = home.camera_jpeg()
        except ConsoleError as error:  # no camera (symbolic), or no image yet
            return _bad("no_camera", request, str(error), 404)
        return Response(jpeg, media_type="image/jpeg",
                        headers={"Cache-Control": "no-store", "X-Homebot-Stamp": f"{stamp:.3f}"})

    @app.get("/api/state")
    def state() -> dict[str, Any]:
        return home.snapshot()

    @app.get("/api/events")
    def events(since: int = Query(0, ge=0, le=2**62)) -> list[dict[str, Any]]:
        return home.events_since(since)

    @app.post("/api/session")
    def session() -> dict[str, Any]:
        secret, name = sessions.open(keep=home.controller)  # a flood never evicts control
        return {"session": secret, "operator": name, "lease": home.lease.seconds}

    @app.post("/api/session/heartbeat")
    def heartbeat(who: str = Depends(operator)) -> dict[str, Any]:
        home.renew_control(who)
        return {"operator": who, "controller": home.controller, "lease_left": home.lease.left()}

    @app.post("/api/session/end")
    def end(who: str = Depends(operator),
            header: str | None = Header(None, alias="X-Homebot-Session"),
            query: str | None = Query(None, alias="session", max_length=64)) -> dict[str, Any]:
        home.release_control(who)
        sessions.close(header or query)
        return {"ended": who, "controller": home.controller}

    @app.post("/api/control")
    def control(body: ControlRequest, who: str = Depends(operator)) -> dict[str, Any]:
        if body.action == "take":
            home.take_control(who)
        else:
            home.require_control(who)
            home.release_control(who)
        return {"controller": home.controller, "lease": home.lease.seconds}

    @app.post("/api/estop")
    def estop() -> dict[str, Any]:
        home.emergency_stop()
        return {"estop": True}

    @app.post("/api/estop/release")
    def release(who: str = Depends(operator)) -> dict[str, Any]:
        home.release_stop(who)
        return {"estop": False}

    @app.post("/api/drive")
    def drive(body: DriveRequest, who: str = Depends(operator)) -> dict[str, Any]:
        twist = home.drive(who, body.vx, body.wz)
        return {"vx": twist.vx, "wz": twist.wz}

    @app.post("/api/command")
    def command(body: CommandRequest, who: str = Depends(operator)) -> dict[str, Any]:
        home.command(who, body.text)
        return {"queued": body.text}

    @app.post("/api/steps")
    def steps(body: StepsRequest, who: str = Depends(operator)) -> dict[str, Any]:
        task = home.run_steps(who, [dict(step) for step in body.steps], body.description)
        return {"queued": task.to_dicts()}

    @app.post("/api/resume")
    def resume(who: str = Depends(operator)) -> dict[str, Any]:
        return {"queued": home.resume(who).to_dicts()}

    @app.websocket("/ws")
    async def live(socket: WebSocket) -> None:  # the guard has checked the token
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


class _NoSession(Exception):
    """No live session named: answered with 403."""
