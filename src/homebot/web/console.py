"""``Console``: one simulated home run for the web console, paced against the wall clock.

The robot's logic lives on simulated time only. The console is the one place where the wall
clock enters: a worker thread runs the home, and the console observes the simulated clock
in steps of at most a body tick, each waiting until the wall clock has caught up with it
(``speed`` times real time; 0 runs as fast as possible). While it waits, it releases the
console's lock, so the server can read a consistent snapshot, take the operator's commands
and press the emergency stop between ticks.

Three levels of teleoperation (Cosero §7.4):

- body: ``drive(vx, wz)`` velocity commands (embodied fidelity), capped and slowed by the
  laser's nearest return ahead; a command holds for ``_COMMAND_HOLD`` simulated seconds;
- skill: ``run_steps`` of one step (navigate to a clicked point, pick a clicked object);
- task: ``command`` (the command box, through ``Conversation``) and ``run_steps`` (composer).

The emergency stop engages the body's own stop (zero velocity from the next tick on) and
cancels the running task's token: the motion under way ends at its next tick (a symbolic
drive, at the next step of the clock) and the task stops there, the robot saying so.
"""

from __future__ import annotations

import io
import logging
import math
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from PIL import Image

from homebot.app import Fidelity, RunSettings, build_run, conversation_for
from homebot.cancel import CancelToken
from homebot.errors import ConsoleError
from homebot.events import Event
from homebot.executive.conversation import Turn
from homebot.executive.narration import Narrator
from homebot.executive.report import RunReport
from homebot.geometry import wrap_angles
from homebot.robot import Body, Twist
from homebot.skills.catalogue import check_step, spelled_as_world
from homebot.skills.places import resolve_target
from homebot.task import Step, Task
from homebot.web.sessions import ControlLease
from homebot.world import World

__all__ = ["VIEW_PERIOD", "Console", "ConsoleSettings", "static_map"]

#: simulated seconds between two images of the head camera drawn for watchers (at most)
VIEW_PERIOD = 0.25

_COMMAND_HOLD = 0.5  #: simulated seconds a body-level velocity command holds
_EVENTS_KEPT = 2000  #: events the console keeps for late-joining watchers
_TRAIL_KEPT = 2000  #: points of the robot's drawn path kept (the page shows the last 200)
_TERMINAL = frozenset({"verified", "failed", "aborted"})
_AHEAD = math.radians(35.0)  #: half-width of the cone "ahead" for obstacle slowing
_SCAN_POINTS_SHOWN = 120
_SLICE = 0.05  #: simulated seconds: the longest single advance (one body tick at 20 Hz)
_UNDER_WAY = frozenset({"running", "finished", "retrying"})
_GO_ON = "go on: "  #: what a task that goes on with a failed one is called, before its name
_log = logging.getLogger("homebot.web")


@dataclass
class ConsoleSettings:
    """What ``homebot serve`` sets: the home, its fidelity, pace, caps and the token."""

    world: World
    token: str
    seed: int = 0
    fidelity: Fidelity = Fidelity.SYMBOLIC
    speed: float = 1.0  #: real-time factor; 0: as fast as possible
    walkers: int = 0
    max_linear: float = 0.4  #: m/s, the body-level cap (below the base's own limit)
    max_angular: float = 1.0  #: rad/s
    time_limit: float | None = 900.0
    lease: float = 10.0  #: wall seconds control lasts without the page's heartbeat


@dataclass
class _Steps:
    """The step view: the task's steps with their status, from the event log."""

    description: str = ""
    steps: list[dict[str, Any]] = field(default_factory=list)
    depth: int = 0
    current: int = -1
    ended: bool | None = None
    reason: str = ""
    outcome: str = ""  #: once ended: done, failed, or stopped (the stop preempted it)


def static_map(world: World) -> dict[str, Any]:
    """The parts of the map that do not move: rooms, doors, furniture, bounds, and an example
    command for this home."""
    rooms = {name: [list(map(float, xy)) for xy in polygon.exterior.coords]
             for name, polygon in world.room_polygons.items()}
    xs = [x for poly in rooms.values() for x, _ in poly]
    ys = [y for poly in rooms.values() for _, y in poly]
    return {
        "type": "map", "name": world.name,
        "bounds": [min(xs), min(ys), max(xs), max(ys)],
        "rooms": rooms,
        "doors": {name: {"x": door.position[0], "y": door.position[1], "width": door.width}
                  for name, door in world.doors.items()},
        "placements": {name: {"box": list(p.footprint.bounds), "room": p.room,
                              "kind": p.model.kind.value}
                       for name, p in world.placements.items()},
        "radius": world.robot.radius,
        "example": example_command(world),
    }


def example_command(world: World) -> str:
    """A command that fits this home, for the command box's placeholder: its first object
    fetched from where it lies (or, with no objects, a trip to its first room)."""
    def spoken(name: str) -> str:
        return name.replace("_", " ")

    if world.model.objects:
        obj = world.model.objects[0]
        return f"bring me the {spoken(obj.name)} from the {spoken(obj.placement)}"
    rooms = list(world.room_polygons)
    return f"go to the {spoken(rooms[0])}" if rooms else "say hello"


class Console:
    """One simulated home, a worker thread that runs it, and the operator's controls."""

    def __init__(self, settings: ConsoleSettings, *,
                 wall: Callable[[], float] = time.monotonic,
                 lease_clock: Callable[[], float] | None = None) -> None:
        """``wall`` paces the home; the control lease reads ``lease_clock`` (default
        ``wall``), which tests step."""
        if not (settings.speed == 0 or (math.isfinite(settings.speed) and settings.speed > 0)):
            raise ConsoleError(f"--speed {settings.speed}: give a real-time factor above 0, "
                               "or 0 for as fast as possible")
        self.settings = settings
        self.world = settings.world
        self.run = build_run(RunSettings(
            world=settings.world, seed=settings.seed, fidelity=settings.fidelity,
            walkers=settings.walkers, time_limit=settings.time_limit))
        self.sim = self.run.simulation
        # a console serves for days: the log and the drawn path keep their latest part only
        self.sim.events.keep = _EVENTS_KEPT
        self.sim.trail_keep = _TRAIL_KEPT
        self.body: Body | None = self.run.body
        self.lock = threading.Condition(threading.RLock())
        self._wall = wall
        self._anchor = (wall(), self.sim.clock.now())
        #: the running task's token; each task gets a fresh one, the stop cancels it
        self._cancel = CancelToken()
        # the one place wall time enters: each step of the simulated clock waits for it
        self.sim.clock.observe(self._paced, step=_SLICE)
        self.events: deque[tuple[int, dict[str, Any]]] = deque(maxlen=_EVENTS_KEPT)
        self.event_count = 0
        self.sim.events.listeners.append(self._heard)
        self.speech: deque[str] = deque(maxlen=20)
        self._jpeg: tuple[float, bytes] | None = None  #: the latest view drawn, encoded
        self._narrator = Narrator()  #: each event's line in the log, as ``do`` narrates
        self.steps = _Steps()
        self._task_open = False  #: a task.start was logged and its task.end not yet
        self.path: list[list[float]] = []
        self.lease = ControlLease(settings.lease, clock=lease_clock or wall)
        self.estop = False
        self.estop_ticks: list[int] = []  #: ticks from each stop press to a standing base
        self._pending_stop: int | None = None
        self._jobs: deque[Callable[[], object]] = deque()
        self._running = False
        self.last_task: Task | None = None
        self.failed_at: int | None = None
        self.help_offer: dict[str, Any] | None = None
        self.last_turn: dict[str, Any] | None = None
        self._teleop = Twist()
        self._teleop_until = -1.0
        self.teleop_scale = 1.0
        self.ticks = 0  #: advances of the simulated clock (a body tick each, when embodied)
        self.tick_hooks: list[Callable[[int], None]] = []  #: called in the worker per advance
        self._closing = False
        self._worker: threading.Thread | None = None
        self.conversation = conversation_for(self.run, runner=self._run_task)

    # ------------------------------------------------------------ the worker

    def start(self) -> None:
        """Start the worker thread (idempotent)."""
        if self._worker is None:
            self._worker = threading.Thread(target=self._work, name="homebot-console",
                                            daemon=True)
            self._worker.start()

    def wait_idle(self, timeout: float) -> bool:
        """Wait (at most ``timeout`` wall seconds) until no task runs or waits to run."""
        with self.lock:
            return self.lock.wait_for(lambda: not self.busy, timeout)

    def close(self) -> None:
        """Stop the worker thread and wait for it."""
        with self.lock:
            self._closing = True
            self._cancel.cancel("the console is closing")
            self.lock.notify_all()
        if self._worker is not None:
            self._worker.join(timeout=10.0)

    def _work(self) -> None:
        with self.lock:
            while not self._closing:
                if self._jobs:
                    job = self._jobs.popleft()
                    self._running, self._cancel = True, CancelToken()
                    try:
                        job()
                    except Exception as error:  # a fault in one task never stops the worker
                        _log.error("a console task failed: %s: %s", type(error).__name__,
                                   error)
                        self.sim.events.record("console.error",
                                               error=f"{type(error).__name__}: {error}")
                    finally:
                        if self._task_open:  # cut short before the task logged its end
                            self.sim.events.record(
                                "task.end", success=False,
                                reason=self._cancel.reason or "the console's task failed")
                        if self._cancel.cancelled:
                            self.sim.events.record("console.preempted",
                                                   reason=self._cancel.reason)
                        self._running = False
                        self._anchor = (self._wall(), self.sim.clock.now())
                        self.lock.notify_all()
                elif self.body is not None and (self.settings.speed > 0 or self._driving()):
                    self.step_body()
                else:
                    self.lock.wait(0.05)

    def _driving(self) -> bool:
        return self.sim.clock.now() <= self._teleop_until

    def step_body(self) -> None:
        """One body tick while no task runs: the operator's velocity, slowed near obstacles."""
        body, localisation = self.body, self.run.localisation
        if body is None:
            raise ConsoleError("driving the base needs a body: serve with --fidelity embodied")
        if self.sim.clock.now() > self._teleop_until or self.estop:
            twist = Twist()
        else:
            twist = self._slowed(self._teleop)
        body.command_velocity(twist)
        body.tick()
        if localisation is not None:  # the robot keeps track of where it is driven
            localisation.update(body.odometry(), body.scan())

    def _paced(self, before: float, now: float) -> None:
        """A step of the simulated clock (at most a body tick): count it, and in the worker
        wait until the wall clock has caught up with it.

        A symbolic move is one long advance; the clock cuts it into steps, so the stop
        cancels it at the next step (before the robot arrives), as the body's own tick
        does when embodied. A cancelled task ends unpaced.
        """
        self.ticks += 1
        for hook in self.tick_hooks:
            hook(self.ticks)
        if self._pending_stop is not None and self.body is not None and \
                self.body.odometry().twist.is_zero():
            self.estop_ticks.append(self.ticks - self._pending_stop)
            self._pending_stop = None
        if threading.current_thread() is not self._worker:
            return
        speed = self.settings.speed
        if speed > 0:
            wall0, sim0 = self._anchor
            target = wall0 + (now - sim0) / speed
            remaining = target - self._wall()
            if remaining < -0.5:  # the home fell behind the wall clock: do not rush to catch up
                self._anchor = (self._wall(), now)
            while remaining > 0 and not self._closing and not self._stopping():
                self.lock.wait(remaining)
                remaining = target - self._wall()
        else:
            self.lock.wait(0)

    @property
    def busy(self) -> bool:
        """A task runs or waits to run."""
        return self._running or bool(self._jobs)

    def _stopping(self) -> bool:
        """A task runs and was cancelled (stop pressed): it ends as fast as it can."""
        return self._running and self._cancel.cancelled

    # ------------------------------------------------------------ events

    def _heard(self, event: Event) -> None:
        data = event.to_dict()
        self.event_count += 1
        kind = event.kind
        if kind in ("robot.laser", "robot.particles", "robot.trajectory"):
            return
        # None: the second record of words the line before says (the page folds it in)
        data["line"] = line = self._narrator.line(kind, event.data)
        self.events.append((self.event_count, data))
        if kind in ("speech", "sim.speech") and line is not None:
            self.speech.append(str(event.data.get("text", "")))
        elif kind == "task.start":
            self._task_open = True
            self.steps = _Steps(str(event.data.get("description", "")),
                                [{**step, "status": "pending"}
                                 for step in event.data.get("steps", [])])
        elif kind == "skill.start":
            self._skill_started(event)
        elif kind == "skill.status":
            self._skill_status(event)
        elif kind == "task.end":
            self._task_open = False
            self._ended(bool(event.data.get("success")), str(event.data.get("reason", "")))

    def _ended(self, success: bool, reason: str) -> None:
        """The step view at the task's end: no step is left under way. A step the stop cut
        short shows ``stopped``; the steps not reached stay ``pending``."""
        view = self.steps
        stopped = not success and self._cancel.cancelled
        view.ended, view.reason, view.depth = success, reason, 0
        view.outcome = "done" if success else "stopped" if stopped else "failed"
        for step in view.steps:
            if step["status"] in _UNDER_WAY or (stopped and step.get("error") == "cancelled"):
                step["status"] = "stopped" if stopped else "failed"

    def _skill_started(self, event: Event) -> None:
        view = self.steps
        skill = str(event.data.get("skill"))
        if view.depth == 0:
            following = view.current + 1
            if following < len(view.steps) and view.steps[following]["skill"] == skill:
                view.current = following
            elif not (0 <= view.current < len(view.steps)
                      and view.steps[view.current]["skill"] == skill):
                view.steps.insert(following, {"skill": skill, "status": "pending",
                                              "recovery": True, **event.data.get("args", {})})
                view.current = following
            view.steps[view.current]["status"] = "running"
            if skill in ("navigate", "guide"):
                self.path = self._planned(event.data.get("args", {}).get("to"))
        view.depth += 1

    def _planned(self, target: Any) -> list[list[float]]:
        """The global plan from here to a navigation target (the robot's own map and
        its beliefs about doors; empty when it cannot be resolved)."""
        goal = resolve_target(self.run.context, target) if target is not None else None
        if goal is None:
            return []
        plan = self.run.context.navigator.plan(self.run.robot.pose().xy(), goal.xy())
        return [] if plan is None else [[round(x, 2), round(y, 2)] for x, y in plan.waypoints]

    def _skill_status(self, event: Event) -> None:
        view = self.steps
        status = str(event.data.get("status"))
        if view.depth == 1 and 0 <= view.current < len(view.steps):
            view.steps[view.current]["status"] = status
            if event.data.get("error"):
                view.steps[view.current]["error"] = event.data["error"]
        if status in _TERMINAL:
            view.depth = max(0, view.depth - 1)

    # ------------------------------------------------------------ operator actions

    @property
    def controller(self) -> str | None:
        """The operator holding control now (None: nobody, or their lease lapsed)."""
        return self.lease.holder

    # control is the lease's alone (it locks itself): taking, renewing and giving it back
    # never wait for the robot, which holds the console's lock while it thinks

    def take_control(self, operator: str) -> None:
        """``operator`` takes control, as a lease their page renews (``renew_control``)."""
        self.lease.take(operator)

    def renew_control(self, operator: str) -> bool:
        """The heartbeat of ``operator``'s page: False when they hold no control (any more)."""
        return self.lease.renew(operator)

    def release_control(self, operator: str) -> None:
        self.lease.release(operator)

    def require_control(self, operator: str) -> None:
        if self.lease.holder != operator:
            raise ConsoleError("take control first (only the operator in control can "
                               "command the robot; control lapses "
                               f"{self.lease.seconds:g} s after their page goes away)")

    def emergency_stop(self) -> None:
        """Stop the base from the next tick on and preempt whatever runs."""
        with self.lock:
            self.estop = True
            self._cancel.cancel("emergency stop")
            self._jobs.clear()
            self._teleop_until = -1.0
            if self.body is not None:
                self.body.emergency_stop(True)
                if not self.body.odometry().twist.is_zero():
                    self._pending_stop = self.ticks
            self.sim.events.record("console.estop")
            self.lock.notify_all()

    def release_stop(self, operator: str) -> None:
        with self.lock:
            self.require_control(operator)
            self.estop = False
            if self.body is not None:
                self.body.emergency_stop(False)
            self.sim.events.record("console.estop_released")
            self.lock.notify_all()

    def drive(self, operator: str, vx: float, wz: float) -> Twist:
        """Body level: a velocity command, capped; held for half a simulated second."""
        with self.lock:
            self.require_control(operator)
            self._check_can_act()
            if self.body is None:
                raise ConsoleError("driving the base needs a body: serve with --fidelity "
                                   "embodied")
            if self.busy:
                raise ConsoleError("a task is running: press stop first, then drive")
            if not (math.isfinite(vx) and math.isfinite(wz)):
                raise ConsoleError("velocities must be numbers")
            cap_v, cap_w = self.settings.max_linear, self.settings.max_angular
            self._teleop = Twist(max(-cap_v, min(cap_v, vx)), 0.0, max(-cap_w, min(cap_w, wz)))
            self._teleop_until = self.sim.clock.now() + _COMMAND_HOLD
            self.lock.notify_all()
            return self._teleop

    def _slowed(self, twist: Twist) -> Twist:
        """Scale forward speed by the nearest laser return ahead (stop near, cap far)."""
        ahead = self.nearest_ahead()
        radius = self.world.robot.radius
        stop, free = radius + 0.15, radius + 1.2
        scale = 1.0 if twist.vx <= 0 else max(0.0, min(1.0, (ahead - stop) / (free - stop)))
        self.teleop_scale = scale
        vx = twist.vx * scale if twist.vx > 0 else max(twist.vx, -0.15)
        return Twist(vx, 0.0, twist.wz)

    def nearest_ahead(self) -> float:
        """The nearest laser return within ±35° of straight ahead (inf: none)."""
        if self.body is None:
            return math.inf
        scan = self.body.scan()
        angles = scan.angle_min + scan.angle_increment * np.arange(len(scan.ranges))
        angles = wrap_angles(angles + scan.mount.theta)
        cone = np.abs(angles) <= _AHEAD
        ranges = np.asarray(scan.ranges)[cone]
        finite = ranges[np.isfinite(ranges)]
        return float(finite.min()) if len(finite) else math.inf

    def run_steps(self, operator: str, steps: list[dict[str, Any]],
                  description: str = "") -> Task:
        """Skill and task level: check the steps against the catalogue and queue them.

        One step run while a failed task waits helps that task (it stays ready to go on).
        """
        with self.lock:
            self.require_control(operator)
            self._check_can_act()
            if not steps:
                raise ConsoleError("give at least one step")
            checked: list[Step] = []
            for index, raw in enumerate(steps, 1):
                if not isinstance(raw, dict) or "skill" not in raw:
                    raise ConsoleError(f"step {index}: give a skill name")
                step = spelled_as_world(Step.from_dict(raw), self.world)
                check_step(step, self.world, f"step {index}")
                checked.append(step)
            task = Task(tuple(checked), description or " then ".join(map(str, checked)))
            # one skill while a failed task waits is the operator helping it on
            helping = len(checked) == 1 and self.failed_at is not None
            self._queue(lambda: self._run_task(task, helping=helping))
            return task

    def command(self, operator: str, text: str) -> None:
        """Task level: a sentence for the robot (or an answer to its question)."""
        with self.lock:
            self.require_control(operator)
            self._check_can_act()
            if not text.strip():
                raise ConsoleError("type a command for the robot")
            self._queue(lambda: self._hear(text))

    def resume(self, operator: str) -> Task:
        """Go on with the failed task from the step that failed, after the operator helped."""
        with self.lock:
            self.require_control(operator)
            self._check_can_act()
            if self.last_task is None or self.failed_at is None:
                raise ConsoleError("no failed task to go on with")
            # named once however often it went on: the description (kept in each
            # task.start event) does not grow with every press
            task = self.last_task.description.removeprefix(_GO_ON)
            rest = Task(self.last_task.steps[self.failed_at:], _GO_ON + task)
            self._queue(lambda: self._run_task(rest))
            return rest

    def _check_can_act(self) -> None:
        if self.estop:
            raise ConsoleError("the emergency stop is engaged: release it first")
        if self.busy or self._jobs:
            raise ConsoleError("the robot is busy: wait, or press stop")

    def _queue(self, job: Callable[[], object]) -> None:
        self._jobs.append(job)
        self.lock.notify_all()

    def _hear(self, text: str) -> None:
        turn: Turn = self.conversation.hear(text)
        self.last_turn = {"heard": turn.heard, "status": turn.status, "said": list(turn.said)}
        if turn.status in ("asked", "refused", "cancelled"):
            for line in turn.said:
                self.speech.append(line)
                self.event_count += 1
                reply = {"text": line}
                self.events.append((self.event_count, {
                    "time": self.sim.clock.now(), "kind": "console.reply", **reply,
                    "line": self._narrator.line("console.reply", reply)}))

    def _run_task(self, task: Task, *, interrupt: Callable[[], bool] | None = None,
                  helping: bool = False) -> RunReport[Any]:
        """Run a task; when it fails, offer the level below and keep it to go on with.

        ``helping``: a single skill the operator runs to help a failed task on; the failed
        task stays ready to go on with, whatever this skill's outcome.
        """
        if not helping:
            self.last_task, self.failed_at, self.help_offer = task, None, None
        report = self.run.run(task, interrupt=interrupt, cancel=self._cancel)
        if not report.success and not helping:
            # the step that failed or was stopped; a stop between two steps: the next one
            index = len(report.steps)
            if report.steps and report.steps[-1].status not in ("verified", "finished"):
                index -= 1
            if index < len(task.steps):
                self.failed_at = index
                self.help_offer = {
                    "step": index, "skill": task.steps[index].skill, "reason": report.reason,
                    "stopped": self._cancel.cancelled,
                    "levels": ["skill", "body"] if self.body is not None else ["skill"],
                }
        return report

    # ------------------------------------------------------------ the view

    def snapshot(self) -> dict[str, Any]:
        """Everything that moves, as one JSON-ready state message (take under the lock)."""
        with self.lock:
            sim = self.sim
            x, y, theta = sim.robot_pose
            state: dict[str, Any] = {
                "type": "state", "time": round(sim.clock.now(), 3),
                "robot": [round(x, 3), round(y, 3), round(theta, 3)],
                "people": {name: [round(p.position[0], 2), round(p.position[1], 2)]
                           for name, p in sim.people.items()},
                "objects": self._objects(),
                "doors": {name: state.value for name, state in sim.door_state.items()},
                "hands": dict(sim.hands),
                "trail": [list(p) for p in sim.trail[-200:]],
                "path": self.path if self.busy else [],
                "speech": list(self.speech)[-5:],
                "task": {"description": self.steps.description, "steps": self.steps.steps,
                         "ended": self.steps.ended, "reason": self.steps.reason,
                         "outcome": self.steps.outcome},
                "help": self.help_offer, "turn": self.last_turn,
                "busy": self.busy, "estop": self.estop, "controller": self.controller,
                "fidelity": self.settings.fidelity.value, "speed": self.settings.speed,
                "teleop_scale": round(self.teleop_scale, 3),
                "events": self.event_count,
            }
            if self.body is not None:
                state.update(self._embodied(self.body))
            return state

    def _objects(self) -> dict[str, Any]:
        sim, shown = self.sim, {}
        for name, where in sim.object_location.items():
            if where is None:
                continue
            if where in self.world.placements:
                px, py = sim.position_on(name, where)
            elif where.startswith("person:") and where[7:] in sim.people:
                px, py = sim.people[where[7:]].position
            else:
                px, py = sim.robot_pose[:2]
            shown[name] = {"at": where, "xy": [round(px, 3), round(py, 3)]}
        return shown

    def _embodied(self, body: Body) -> dict[str, Any]:
        scan = body.scan()
        ranges = np.asarray(scan.ranges)
        x, y, theta = self.sim.robot_pose
        step = max(1, len(ranges) // _SCAN_POINTS_SHOWN)
        points = []
        for index in range(0, len(ranges), step):
            r = ranges[index]
            if math.isfinite(r):
                a = theta + scan.mount.theta + scan.angle_min + index * scan.angle_increment
                points.append([round(x + r * math.cos(a), 2), round(y + r * math.sin(a), 2)])
        localisation = self.run.localisation
        particles = localisation.particles if localisation is not None else np.zeros((0, 3))
        if len(particles) > 150:
            particles = particles[:: math.ceil(len(particles) / 150)]
        frame = body.last_camera()
        return {"scan": points, "camera": None if frame is None else round(frame.stamp, 3),
                "particles": np.round(np.asarray(particles)[:, :2], 2).tolist(),
                "nearest_ahead": round(min(self.nearest_ahead(), 99.0), 3),
                "velocity": [round(body.odometry().twist.vx, 3),
                             round(body.odometry().twist.wz, 3)]}

    def camera_jpeg(self) -> tuple[float, bytes]:
        """What the head camera sees now, as JPEG, with its stamp (simulated seconds).

        Drawn for the watcher (``Body.view``), not taken by the robot, so a watched run is
        the run unwatched; at most once per ``VIEW_PERIOD`` of simulated time, however
        many pages ask (within it, they share the image drawn last).
        """
        if self.body is None:
            raise ConsoleError("no camera: the console serves the symbolic home; serve with "
                               "--fidelity embodied to see through the robot's head camera")
        with self.lock:  # between two ticks: the home stands still while it is drawn
            now = self.sim.clock.now()
            if self._jpeg is not None and 0.0 <= now - self._jpeg[0] < VIEW_PERIOD:
                return self._jpeg
            frame = self.body.view()
        if frame is None:
            raise ConsoleError("no camera image yet: the robot's body sends one when it "
                               "looks")
        encoded = io.BytesIO()
        Image.fromarray(np.ascontiguousarray(frame.rgb)).save(encoded, "JPEG", quality=85)
        self._jpeg = (frame.stamp, encoded.getvalue())
        return self._jpeg

    def events_since(self, number: int) -> list[dict[str, Any]]:
        """The kept events numbered above ``number``, each with its number as ``n``."""
        with self.lock:
            return [{"n": n, **data} for n, data in self.events if n > number]
