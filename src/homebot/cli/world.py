"""``homebot world check|show``: validate a world file, or show one as a table, JSON or PNG."""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
from dataclasses import astuple
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rich.console import Console
from rich.table import Table

from homebot.cli.options import load_world
from homebot.errors import WorldError
from homebot.events import EventLog
from homebot.files import read_text_file
from homebot.world import World

if TYPE_CHECKING:
    from homebot.viz import EmbodiedRun, FinalState

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
    if args.png:
        from homebot.viz import render_map

        if args.png.suffix.lower() != ".png":
            raise WorldError(f"{args.png}: the map is a PNG image; give a name ending in .png")
        events = args.events or last_run_path()
        if args.events is not None and not args.events.is_file():
            raise WorldError(f"--events {args.events}: no such file; give the file written "
                             "by run-task or do --events")
        image = render_map(world, _path_from_events(events, world),
                           _embodied_from_events(events, world),
                           _final_from_events(events, world))
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


def _path_from_events(events: Path, world: World) -> list[tuple[float, float]]:
    if not events.exists():
        return []
    start = world.robot.pose.xy()
    path: list[tuple[float, float]] = [start]
    try:
        for line in read_text_file(events, WorldError, "events", "event log").splitlines():
            event = json.loads(line)
            if event.get("kind") == "robot.path" and event.get("world") == world.name:
                path.extend((float(x), float(y)) for x, y in event["points"])
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        raise WorldError(f"{events}: not a homebot event log (JSON lines); give the file "
                         "written by run-task --events") from None
    return path if len(path) > 1 else []


def _embodied_from_events(events: Path, world: World) -> EmbodiedRun | None:
    """The trajectory, particles and laser of an embodied run logged in ``events``."""
    from homebot.viz import embodied_run

    if not events.exists():
        return None
    try:
        lines = read_text_file(events, WorldError, "events", "event log").splitlines()
        return embodied_run((json.loads(line) for line in lines if line.strip()), world.name)
    except (OSError, ValueError, TypeError, KeyError, AttributeError) as error:
        raise WorldError(f"{events}: not a homebot event log of an embodied run ({error}); "
                         "give the file written by run-task --events") from None


def _final_from_events(events: Path, world: World) -> FinalState | None:
    """Where the run logged in ``events`` left objects, people, doors and the robot."""
    from homebot.viz import final_state

    if not events.exists():
        return None
    try:
        lines = read_text_file(events, WorldError, "events", "event log").splitlines()
        return final_state((json.loads(line) for line in lines if line.strip()), world.name)
    except (OSError, ValueError, TypeError, KeyError, AttributeError) as error:
        raise WorldError(f"{events}: its final state cannot be read ({error}); give the file "
                         "written by run-task --events") from None


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
