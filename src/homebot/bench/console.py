"""The web console: e-stop within one tick (navigation, follow) and 20 watchers at 10 updates/s.

The e-stop trials run the embodied robot in the console's worker as fast as possible and
press the stop at a seeded tick of a running navigation or follow; a trial passes when the
base stands from the next tick on (``ticks`` ≤ 1) and the true pose (ground truth) does not
move after the press. The load test serves the console on loopback (uvicorn, real time) and
connects ``--clients`` websocket watchers for ``--seconds`` wall seconds; it reports each
update's latency (server send to client receipt, same machine clock), its p95, and the
updates dropped beyond the back-pressure policy (a state superseded while its watcher was
still sending is the policy; any other gap in the sequence numbers is a drop).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import random
import secrets
import socket
import statistics
import threading
import time
from dataclasses import dataclass
from typing import Any

from rich.console import Console as Terminal

from homebot.app import Fidelity
from homebot.bench.arguments import count, seed
from homebot.progress import track
from homebot.web import Console, ConsoleSettings
from homebot.world import World

__all__ = ["StopTrial", "add_arguments", "estop_trials", "load_test", "run"]

_OPERATOR = "bench"
_FOREVER = math.inf  #: the benchmark is an operator whose page never goes away: no lapse
_TRIAL_TIMEOUT = 60.0  #: wall seconds a trial may take before it counts as failed


@dataclass(frozen=True)
class StopTrial:
    """One press of the e-stop: ticks until the base stood, how far it moved after."""

    kind: str
    pressed_at_tick: int
    ticks: int | None
    moved_after: float
    preempted: bool

    @property
    def passed(self) -> bool:
        return self.ticks is not None and self.ticks <= 1 and self.moved_after == 0.0 and \
            self.preempted


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--trials", type=count("--trials", 1, 200), default=20,
                        help="e-stop presses during navigation, and as many during follow")
    parser.add_argument("--clients", type=count("--clients", 0, 200), default=20,
                        help="watching websocket clients (0: no load test)")
    parser.add_argument("--seconds", type=count("--seconds", 1, 600), default=60,
                        help="how long the load test watches, wall seconds")
    parser.add_argument("--rate", type=count("--rate", 1, 100), default=10,
                        help="updates a second the server sends each watcher")
    parser.add_argument("--seed", type=seed, default=0, help="seed of the press ticks")


def run(args: argparse.Namespace, console: Terminal | None = None) -> dict[str, Any]:
    world = World.load("apartment")
    figures: dict[str, Any] = {}
    for kind in ("navigation", "follow"):
        trials = estop_trials(world, kind, args.trials, args.seed)
        figures[f"estop_{kind}"] = {
            "passed": sum(t.passed for t in trials), "tries": len(trials),
            "max_ticks": max((t.ticks for t in trials if t.ticks is not None), default=None),
            "max_moved_after_m": max(t.moved_after for t in trials)}
    if args.clients:
        figures["load"] = load_test(world, args.clients, args.rate, float(args.seconds))
    if console is not None:
        for name, values in figures.items():
            console.print(f"{name}: {values}")
    return {"benchmark": "console", "figures": figures}


# ---------------------------------------------------------------- e-stop

_GOALS = {"navigation": [[{"skill": "navigate", "to": "office"}],
                         [{"skill": "navigate", "to": "kitchen"}],
                         [{"skill": "navigate", "to": "bedroom"}]],
          "follow": [[{"skill": "follow", "person": "Alex", "to": "office"}],
                     [{"skill": "follow", "person": "Alex", "to": "living room"}]]}
_ATTEMPTS = 3  #: tries per press, when the robot did not get to move before the press


def estop_trials(world: World, kind: str, trials: int, seed: int) -> list[StopTrial]:
    """Press the e-stop ``trials`` times while the robot navigates (or follows someone)."""
    home = Console(ConsoleSettings(world=world, token="bench-token", seed=seed,
                                   fidelity=Fidelity.EMBODIED, speed=0.0, lease=_FOREVER))
    rng = random.Random(f"{seed}:{kind}")
    results: list[StopTrial] = []
    home.start()
    try:
        home.take_control(_OPERATOR)
        for trial in track(range(trials), f"e-stop trials, {kind}"):
            for _ in range(_ATTEMPTS):
                if kind == "follow":
                    _person_beside_the_robot(home, "Alex")
                result = _one_press(home, kind, _GOALS[kind][trial % len(_GOALS[kind])],
                                    rng.randint(20, 120))
                home.release_stop(_OPERATOR)
                if result.ticks is not None or result.preempted:
                    break
            results.append(result)
    finally:
        home.close()
    return results


def _person_beside_the_robot(home: Console, person: str) -> None:
    """Set-up (ground truth): the person to follow stands next to the robot."""
    with home.lock:
        spot = home.sim.spot_aside(home.sim.robot_pose[:2])
        if spot is not None:
            home.sim.move_person(person, spot)


def _one_press(home: Console, kind: str, steps: list[dict[str, Any]], after: int) -> StopTrial:
    """Run ``steps``; ``after`` ticks into the motion skill, press the stop from the worker."""
    pressed: dict[str, Any] = {}
    motion = "follow" if kind == "follow" else "navigate"
    body = home.body
    assert body is not None, "the e-stop trials run an embodied console"

    def hook(tick: int) -> None:
        if "tick" in pressed or home.steps.current < 0:
            return
        step = home.steps.steps[home.steps.current]
        if step["skill"] != motion or step["status"] != "running":
            return
        pressed.setdefault("first", tick)
        moving = not body.odometry().twist.is_zero()
        if tick - pressed["first"] >= after and moving:
            pressed["tick"] = tick
            pressed["pose"] = home.sim.robot_pose
            before = len(home.estop_ticks)
            pressed["before"] = before
            home.emergency_stop()

    home.tick_hooks.append(hook)
    preempted_before = sum(1 for _ in home.sim.events.of_kind("console.preempted"))
    try:
        home.run_steps(_OPERATOR, steps, f"{kind} trial")
        idle = home.wait_idle(_TRIAL_TIMEOUT)
    finally:
        home.tick_hooks.remove(hook)
    if not idle or "tick" not in pressed:
        home.emergency_stop()
        home.wait_idle(_TRIAL_TIMEOUT)
        return StopTrial(kind, -1, None, math.inf, False)
    with home.lock:
        ticks = home.estop_ticks[-1] if len(home.estop_ticks) > pressed["before"] else None
        here = home.sim.robot_pose
        preempted = sum(1 for _ in home.sim.events.of_kind("console.preempted")) > \
            preempted_before
    moved = math.dist(here[:2], pressed["pose"][:2])
    return StopTrial(kind, pressed["tick"], ticks, moved, preempted)


# ---------------------------------------------------------------- load


def load_test(world: World, clients: int, rate: int, seconds: float) -> dict[str, Any]:
    """Serve the console on loopback and watch it with ``clients`` websockets."""
    import uvicorn

    from homebot.web.app import create_app

    token = secrets.token_urlsafe(12)
    settings = ConsoleSettings(world=world, token=token, speed=1.0, lease=_FOREVER)
    app = create_app(settings, rate=float(rate))
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port,
                                           log_level="warning", ws_max_queue=64))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    for _ in range(400):  # at most 20 s for the server to listen
        if server.started:
            break
        thread.join(0.05)
    done = threading.Event()
    commander = threading.Thread(target=_keep_busy, args=(app.state.console, done), daemon=True)
    commander.start()
    try:
        results = asyncio.run(_watch_all(port, token, clients, seconds))
    finally:
        done.set()
        app.state.console.emergency_stop()
        commander.join(timeout=10.0)
        server.should_exit = True
        thread.join(timeout=10.0)
    stats = app.state.stats
    tasks = sum(1 for _ in app.state.console.sim.events.of_kind("task.end"))
    latencies = sorted(value for result in results for value in result["latencies"])
    gaps = sum(result["gaps"] for result in results)
    received = sum(len(result["latencies"]) for result in results)
    expected = clients * seconds * rate
    return {
        "clients": clients, "seconds": seconds, "rate": rate,
        "updates_received": received, "updates_expected_about": round(expected),
        "latency_p50_ms": _ms(statistics.median(latencies)) if latencies else None,
        "latency_p95_ms": _ms(latencies[int(0.95 * (len(latencies) - 1))]) if latencies else None,
        "latency_max_ms": _ms(latencies[-1]) if latencies else None,
        "gaps_in_sequence": gaps,
        "superseded_by_policy": stats["superseded"],
        "dropped_beyond_policy": max(0, gaps - stats["superseded"]),
        "events_lost": stats["lost_events"],
        "tasks_run_meanwhile": tasks,
    }


_COMMANDS = ("bring me a coke from the kitchen", "go to the office", "go to the living room")


def _keep_busy(home: Console, done: threading.Event) -> None:
    """Keep the robot busy with commands while the watchers watch."""
    home.take_control(_OPERATOR)
    index = 0
    while not done.is_set():
        if home.wait_idle(0.5) and not done.is_set():
            home.command(_OPERATOR, _COMMANDS[index % len(_COMMANDS)])
            index += 1


def _ms(seconds: float) -> float:
    return round(seconds * 1000.0, 1)


async def _watch_all(port: int, token: str, clients: int, seconds: float) -> list[dict[str, Any]]:
    import websockets

    async def watch() -> dict[str, Any]:
        latencies: list[float] = []
        gaps, last = 0, None
        url = f"ws://127.0.0.1:{port}/ws?token={token}"
        async with websockets.connect(url, max_size=2**22) as ws:
            end = time.monotonic() + seconds
            while (left := end - time.monotonic()) > 0:
                try:
                    text = await asyncio.wait_for(ws.recv(), timeout=left)
                except TimeoutError:
                    break
                message = json.loads(text)
                if message.get("type") != "state":
                    continue
                latencies.append(time.time() - message["sent"])
                if last is not None and message["seq"] != last + 1:
                    gaps += message["seq"] - last - 1
                last = message["seq"]
        return {"latencies": latencies, "gaps": gaps}

    return list(await asyncio.gather(*(watch() for _ in range(clients))))
