"""``homebot world from-robocup DIR -o WORLD.yaml``: a playable world from RoboCup@Home data."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from homebot.world import World
from homebot.world.robocup import import_robocup
from homebot.world.writing import write_world_yaml

__all__ = ["register_robocup"]


def register_robocup(world_subparsers: Any) -> None:
    """Add ``from-robocup`` to the ``world`` command group."""
    parser = world_subparsers.add_parser(
        "from-robocup", help="build a world from a RoboCup@Home data directory")
    parser.add_argument("directory", type=Path,
                        help="directory with names/, maps/ and objects/ (markdown tables)")
    parser.add_argument("-o", "--output", type=Path, required=True, help="world YAML to write")
    parser.add_argument("--name", help="name of the world (default: the directory's name)")
    parser.add_argument("--rooms", type=Path, metavar="FILE",
                        help="YAML of 'location: room' lines, looked up before the shipped "
                             "common-sense table (bed: bedroom, sink: kitchen ...)")
    parser.set_defaults(handler=_from_robocup)


def _from_robocup(args: argparse.Namespace) -> int:
    imported = import_robocup(args.directory, name=args.name, rooms_file=args.rooms)
    for warning in imported.warnings:
        print(f"warning: {warning}", file=sys.stderr)
    data = imported.data
    world = World.from_dict(data, source=str(args.directory), origin=imported.origin)
    header = (f"Built by `homebot world from-robocup {args.directory}`.\n"
              f"The robot starts at the entrance; {data['operator']} is the operator.")
    write_world_yaml(args.output, data, header)
    print(f"{args.output}: {len(world.rooms)} rooms, {len(world.doors)} doors, "
          f"{len(world.placements)} placements, {len(world.objects)} objects, "
          f"{len(world.people)} people")
    return 0
