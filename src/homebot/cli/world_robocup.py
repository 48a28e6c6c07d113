"""``homebot world from-robocup DIR -o WORLD.yaml``: a playable world from RoboCup@Home data."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

import yaml

from homebot.errors import WorldError
from homebot.world import World
from homebot.world.robocup import world_from_robocup

__all__ = ["register_robocup"]


def register_robocup(world_subparsers: Any) -> None:
    """Add ``from-robocup`` to the ``world`` command group."""
    parser = world_subparsers.add_parser(
        "from-robocup", help="build a world from a RoboCup@Home data directory")
    parser.add_argument("directory", type=Path,
                        help="directory with names/, maps/ and objects/ (markdown tables)")
    parser.add_argument("-o", "--output", type=Path, required=True, help="world YAML to write")
    parser.add_argument("--name", help="name of the world (default: the directory's name)")
    parser.set_defaults(handler=_from_robocup)


def _from_robocup(args: argparse.Namespace) -> int:
    data = world_from_robocup(args.directory, name=args.name)
    world = World.from_dict(data, source=str(args.directory))
    try:
        args.output.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    except OSError as error:
        raise WorldError(f"{args.output}: cannot be written ({error})") from None
    print(f"{args.output}: {len(world.rooms)} rooms, {len(world.doors)} doors, "
          f"{len(world.placements)} placements, {len(world.objects)} objects, "
          f"{len(world.people)} people")
    return 0
