"""``homebot world map|map-check``: a world's occupancy grid as a ROS map_server map, and back."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from homebot.world import World

__all__ = ["register_map"]


def register_map(world_parsers: Any) -> None:
    """Add ``map`` and ``map-check`` to the ``world`` command group."""
    write = world_parsers.add_parser(
        "map", help="write the world's occupancy grid as a ROS map_server YAML + PGM")
    write.add_argument("--world", default="apartment", help="world file or shipped name")
    write.add_argument("-o", "--output", type=Path, required=True, metavar="DIR",
                       help="folder for WORLD.yaml and WORLD.pgm (made if missing)")
    write.set_defaults(handler=_write)
    check = world_parsers.add_parser(
        "map-check", help="read a ROS map_server map back and count its cells")
    check.add_argument("file", type=Path, help="the map's YAML file")
    check.add_argument("--world", help="also check that the map covers this world")
    check.add_argument("--json", action="store_true", help="print the figures as JSON")
    check.set_defaults(handler=_check)


def _write(args: argparse.Namespace) -> int:
    from homebot.navigation.map_io import RosMap, map_file_stem, write_map

    world = World.load(args.world)
    yaml_path, pgm_path = write_map(RosMap.from_world(world),
                                    args.output / f"{map_file_stem(world)}.yaml")
    print(f"wrote {yaml_path} and {pgm_path}")
    return 0


def _check(args: argparse.Namespace) -> int:
    from homebot.navigation.map_io import RosMap, read_map

    ros_map = read_map(args.file)
    differing = None
    if args.world:
        world = World.load(args.world)
        ros_map.check_covers(world)
        differing = ros_map.differing_cells(RosMap.from_world(world))
    rows, columns = ros_map.shape
    counts = ros_map.counts()
    if args.json:
        print(json.dumps({"file": str(args.file), "width": columns, "height": rows,
                          "resolution": ros_map.resolution, "origin": list(ros_map.origin),
                          **counts, "world": args.world, "differing_cells": differing}))
        return 0
    x, y, yaw = ros_map.origin
    covers = f"; covers world '{args.world}'" if args.world else ""
    if differing is not None:
        covers += f", free floor differs in {differing} cells"
    print(f"{args.file}: {columns}×{rows} cells at {ros_map.resolution:g} m, origin "
          f"({x:g}, {y:g}, {yaw:g}); free {counts['free']}, occupied {counts['occupied']}, "
          f"unknown {counts['unknown']}{covers}")
    return 0
