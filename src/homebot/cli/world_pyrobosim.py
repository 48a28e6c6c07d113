"""``homebot world from-pyrobosim FILE -o WORLD.yaml``: a homebot world from a pyrobosim world."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from homebot.world import World
from homebot.world.pyrobosim import import_pyrobosim
from homebot.world.writing import write_world_yaml

__all__ = ["register_pyrobosim"]


def register_pyrobosim(world_subparsers: Any) -> None:
    """Add ``from-pyrobosim`` to the ``world`` command group."""
    parser = world_subparsers.add_parser(
        "from-pyrobosim", help="import a pyrobosim world YAML (rooms, hallways, locations, "
                               "objects)")
    parser.add_argument("file", type=Path, help="a pyrobosim world file")
    parser.add_argument("-o", "--output", type=Path, required=True, help="world YAML to write")
    parser.add_argument("--operator", default="Alex",
                        help="name of the person beside the robot who gives commands "
                             "(pyrobosim worlds have no people; default: Alex)")
    parser.set_defaults(handler=_from_pyrobosim)


def _from_pyrobosim(args: argparse.Namespace) -> int:
    imported = import_pyrobosim(args.file, operator=args.operator)
    for warning in imported.warnings:
        print(f"warning: {warning}", file=sys.stderr)
    data = imported.data
    world = World.from_dict(data, source=str(args.file))
    header = (f"Imported by `homebot world from-pyrobosim {args.file}`: hallways are rooms of\n"
              f"their own with a door where they meet a room; {args.operator} is the operator.")
    write_world_yaml(args.output, data, header)
    print(f"{args.output}: {len(world.rooms)} rooms (with hallways), {len(world.doors)} doors, "
          f"{len(world.placements)} placements, {len(world.objects)} objects")
    return 0
