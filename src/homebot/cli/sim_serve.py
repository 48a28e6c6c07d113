"""``homebot sim serve``: a simulated robot on ROS 2 (/map, /odom, /tf, NavigateToPose)."""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import TYPE_CHECKING, Any

from homebot.app import RunSettings, build_run, disturbed
from homebot.cli.options import (
    add_fidelity_option,
    add_world_options,
    disturbance_level,
    load_world,
    walker_count,
    whole_number,
)
from homebot.cli.ros_options import (
    SERVER_KEEP,
    add_transport_options,
    serve_logging,
    transport_node,
)
from homebot.world import World

if TYPE_CHECKING:
    from homebot.transport.node import Node

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("sim", help="serve the simulated robot over ROS 2")
    commands = parser.add_subparsers(dest="sim_command", metavar="COMMAND")
    serve = commands.add_parser("serve", help="publish a simulated robot the way a real one "
                                              "would (until stopped)")
    add_world_options(serve)
    add_transport_options(serve)
    add_fidelity_option(serve)
    serve.add_argument("--disturb", type=disturbance_level, default=0.0, metavar="LEVEL",
                       help="switch disturbances on (1 = the benchmark's level)")
    serve.add_argument("--crash-after", type=whole_number(0, 1_000_000), default=0, metavar="N",
                       help="fault injection: end the process abruptly (as a crash or kill "
                            "would) after answering N robot calls (default 0: never)")
    serve.add_argument("--body", action="store_true",
                       help="serve the robot's body instead (/cmd_vel in; /scan, /odom, /tf "
                            "out; one tick per /cmd_vel) for RosBody")
    serve.add_argument("--walkers", type=walker_count, default=0, metavar="N",
                       help="--body: how many people walk about on their own (default 0)")
    serve.set_defaults(handler=_serve)
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)


def _serve(args: argparse.Namespace) -> int:
    serve_logging()
    node = transport_node(args)
    from homebot.transport.sim_server import SimServer

    world = load_world(args)
    if args.body:
        return _serve_body(args, node, world)
    run = build_run(RunSettings(
        world=world, seed=args.seed, fidelity=args.fidelity,
        disturbances=disturbed(args.disturb) if args.disturb else None))
    run.events.keep = run.simulation.trail_keep = SERVER_KEEP
    server = SimServer(node, run.robot, world, run.events, final_state=run.record_final_state)
    print(f"homebot sim serve: {world.name}, seed {args.seed}, ROS 2 domain {args.domain_id} "
          f"on {args.interface}", flush=True)
    try:
        while True:
            server.spin_once(0.2)
            if 0 < args.crash_after <= server.calls_served:
                print(f"homebot sim serve: crashing on purpose at {time.time():.3f} "
                      "(--crash-after)", file=sys.stderr, flush=True)
                os._exit(3)  # no clean-up, no goodbye to DDS peers: as a kill -9
    except KeyboardInterrupt:
        return 0


def _serve_body(args: argparse.Namespace, node: Node, world: World) -> int:
    from homebot.app.ros import serve_simulated_body

    server = serve_simulated_body(node, RunSettings(
        world=world, seed=args.seed, walkers=args.walkers,
        disturbances=disturbed(args.disturb) if args.disturb else None))
    print(f"homebot sim serve --body: {world.name}, seed {args.seed}, ROS 2 domain "
          f"{args.domain_id} on {args.interface}", flush=True)
    try:
        while True:
            server.spin_once(0.2)
    except KeyboardInterrupt:
        return 0
