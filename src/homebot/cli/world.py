"""``homebot world check|show``: validate a world file, or show one as a table, JSON or PNG."""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import sys
from dataclasses import astuple
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.cli.options import load_world
from homebot.errors import WorldError
from homebot.events import EventLog
from homebot.files import read_text_file
from homebot.text import problem_listing, terminal_safe
from homebot.world import World
from homebot.yamlfile import short_repr

__all__ = ["last_run_path", "register", "remember_last_run", "world_summary"]


def last_run_path() -> Path:
    """Where the current project's last simulated run is kept (for ``world show``).

    The project is the folder homebot runs in (``$HOMEBOT_PROJECT`` when set): its
    ``.homebot/last-run.jsonl``, so two projects (or two checkouts) never draw each
    other's runs. ``--events FILE`` names any other run.
    """
    project = Path(os.environ.get("HOMEBOT_PROJECT") or Path.cwd())
    return project / ".homebot" / "last-run.jsonl"


def remember_last_run(events: EventLog) -> None:
    """Keep a run's event log so ``world show --png`` can draw its path."""
    path = last_run_path()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        events.write(path)
    except OSError:
        pass  # the map of the last run is a convenience, never a reason to fail a task


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("world", help="check or show a world")
    world_parsers = parser.add_subparsers(dest="world_command", metavar="COMMAND")
    check = world_parsers.add_parser("check", help="validate a world file")
    check.add_argument("file", help="world YAML file (or a shipped world name)")
    check.set_defaults(handler=_check)
    show = world_parsers.add_parser("show", help="list a world, or draw it as a PNG")
    show.add_argument("--world", default="apartment", help="world file or shipped name")
    show.add_argument("--png", type=Path,
                      help="draw the map here: legend, scale, the robot's heading, and the "
                           "run's path and where it left objects, people and doors")
    show.add_argument("--events", type=Path,
                      help="event log of the run to draw (default: this project's last run, "
                           ".homebot/last-run.jsonl in the current folder)")
    show.add_argument("--json", action="store_true", help="print the world's entities as JSON")
    show.set_defaults(handler=_show)
    if importlib.util.find_spec("homebot.cli.world_robocup") is not None:
        from homebot.cli import world_robocup

        world_robocup.register_robocup(world_parsers)
    from homebot.cli.world_pyrobosim import register_pyrobosim

    register_pyrobosim(world_parsers)
    from homebot.cli.world_map import register_map

    register_map(world_parsers)
    parser.set_defaults(handler=lambda args: _no_command())


def _no_command() -> int:
    raise WorldError("name a world command: check FILE, show [--world W], "
                     "from-robocup DIR -o WORLD.yaml, from-pyrobosim FILE -o WORLD.yaml, "
                     "map [--world W] -o DIR, "
                     "map-check FILE.yaml")


def _check(args: argparse.Namespace) -> int:
    world = World.load(args.file)
    if world.warnings:
        print(terminal_safe(problem_listing([f"warning: {warning}" for warning in
                                             world.warnings]), lines=True), file=sys.stderr)
    print(f"{world.source}: ok — {len(world.rooms)} rooms, {len(world.doors)} doors, "
          f"{len(world.placements)} placements, {len(world.objects)} objects, "
          f"{len(world.people)} people")
    return 0


def world_summary(world: World) -> dict[str, Any]:
    """Rooms, doors, placements, objects and people with their attributes."""
    return {
        "name": world.name,
        "rooms": [{"name": name, "polygon": [list(p) for p in room.polygon]}
                  for name, room in world.rooms.items()],
        "doors": [{"name": d.name, "rooms": list(d.rooms), "position": list(d.position),
                   "state": d.state.value} for d in world.doors.values()],
        "placements": [{"name": p.name, "category": p.category, "room": p.room,
                        "kind": p.model.kind.value, "approach": list(astuple(p.approach)),
                        "holds": list(p.holds)} for p in world.placements.values()],
        "objects": [{"name": o.name, "category": o.category, "placement": o.placement}
                    for o in world.objects.values()],
        "people": [{"name": p.name, "room": p.room, "position": list(p.position),
                    "posture": p.posture.value, "gesture": p.gesture.value,
                    "clothes": list(p.clothes)} for p in world.people.values()],
        "operator": world.model.operator,
        "robot": {"pose": list(astuple(world.robot.pose)), "hands": list(world.robot.hands)},
    }


def _show(args: argparse.Namespace) -> int:
    world = load_world(args)
    if args.events is not None and not args.png:
        raise WorldError(f"--events {args.events}: the run is drawn on the map; give --png "
                         "FILE.png too")
    if args.png:
        from homebot.viz import embodied_run, final_state, render_map

        if args.png.suffix.lower() != ".png":
            raise WorldError(f"{args.png}: the map is a PNG image; give a name ending in .png")
        if args.events is not None and not args.events.is_file():
            raise WorldError(f"--events {args.events}: no such file; give the file written "
                             "by run-task or do --events")
        path = args.events or last_run_path()
        events = _read_event_log(path, world) if path.is_file() else []
        try:
            embodied = embodied_run(events, world.name)
        except (ValueError, TypeError, KeyError, AttributeError) as error:
            raise WorldError(f"{path}: not a homebot event log of an embodied run ({error}); "
                             "give the file written by run-task --events") from None
        try:
            final = final_state(events, world.name)
        except (ValueError, TypeError, KeyError, AttributeError) as error:
            raise WorldError(f"{path}: its final state cannot be read ({error}); give the file "
                             "written by run-task --events") from None
        image = render_map(world, _path_from_events(events, world), embodied, final)
        try:
            image.save(args.png)
        except OSError as error:
            raise WorldError(f"{args.png}: cannot be written ({error.strerror or error}); "
                             "check that its folder exists and is writable") from None
        print(f"wrote {args.png}")
    if args.json:
        print(json.dumps(world_summary(world), ensure_ascii=False))
    elif not args.png:
        _print_tables(world)
    return 0


#: metres a drawn point may lie beyond the rooms' bounds (a robot's path hugs the walls)
_DRAWN_MARGIN = 5.0


def _read_event_log(path: Path, world: World) -> list[dict[str, Any]]:
    """The events of a JSON-lines log, each point to draw checked to lie on the map.

    Raises ``WorldError`` naming the file and line of anything that is not an event, of a
    number that is not finite (``NaN``), and of a point far outside the world.
    """
    lines = read_text_file(path, WorldError, "events", "event log").splitlines()
    events = []
    for number, line in enumerate(lines, start=1):
        if not line.strip():
            continue
        try:
            event = json.loads(line, parse_constant=_no_constant, parse_float=_finite)
        except (ValueError, RecursionError) as error:
            raise WorldError(f"{path}: line {number}: not a homebot event log ({error}); give "
                             "the file written by run-task --events") from None
        if not isinstance(event, dict):
            raise WorldError(f"{path}: line {number}: not a homebot event log (each line "
                             "is a JSON object); give the file written by run-task --events")
        if event.get("world", world.name) == world.name:
            _check_drawn_points(event, world, f"{path}: line {number}")
        events.append(event)
    return events


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is no number")


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is too large a number")
    return value


def _check_drawn_points(event: dict[str, Any], world: World, where: str) -> None:
    """Every point of the event that is drawn lies within the world's bounds, give or take
    ``_DRAWN_MARGIN`` metres."""
    kind = event.get("kind")
    points: list[Any] = []
    if kind in ("robot.path", "robot.trajectory") and isinstance(event.get("points"), list):
        points = event["points"]
    elif kind == "sim.final":
        points = [event["robot"]] if event.get("robot") is not None else []
        if isinstance(event.get("people"), dict):
            points += list(event["people"].values())
    min_x, min_y, max_x, max_y = world.bounds()
    for point in points:
        if not isinstance(point, list) or len(point) < 2 or not all(
                isinstance(value, int | float) and not isinstance(value, bool)
                for value in point[:2]):
            raise WorldError(f"{where}: {kind} holds {short_repr(point)}, not a point "
                             "[x, y]; give the file written by run-task --events")
        x, y = float(point[0]), float(point[1])
        beyond = max(min_x - x, x - max_x, min_y - y, y - max_y)
        if beyond > _DRAWN_MARGIN:
            raise WorldError(f"{where}: {kind} point {short_repr(point)} lies {beyond:.3g} m "
                             f"outside the world '{world.name}' (x {min_x:g} to {max_x:g}, "
                             f"y {min_y:g} to {max_y:g} m); give the event log of a run in "
                             "this world")


def _path_from_events(events: list[dict[str, Any]], world: World) -> list[tuple[float, float]]:
    """The symbolic robot's path (``robot.path`` events of ``world``), from its start."""
    start = world.robot.pose.xy()
    path: list[tuple[float, float]] = [start]
    for event in events:
        if event.get("kind") == "robot.path" and event.get("world") == world.name:
            path.extend((float(x), float(y)) for x, y, *_ in event["points"])
    return path if len(path) > 1 else []


def _print_tables(world: World) -> None:
    console = Console()
    console.print(f"[bold]{world.name}[/]: {world.model.description}")
    table = Table("placement", "category", "room", "holds", "objects on it")
    for placement in world.placements.values():
        objects = [o.name for o in world.objects.values() if o.placement == placement.name]
        table.add_row(placement.name, placement.category, placement.room,
                      ", ".join(placement.holds), ", ".join(objects))
    console.print(table)
    people = Table("person", "room", "posture", "gesture", "clothes")
    for person in world.people.values():
        people.add_row(person.name, person.room, person.posture.value, person.gesture.value,
                       ", ".join(person.clothes))
    console.print(people)
    doors = Table("door", "between", "state")
    for door in world.doors.values():
        doors.add_row(door.name, " and ".join(door.rooms), door.state.value)
    console.print(doors)
