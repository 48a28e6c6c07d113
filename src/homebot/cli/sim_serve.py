"""``homebot sim serve``: a simulated robot on ROS 2 (/map, /odom, /tf, NavigateToPose)."""

from __future__ import annotations

import argparse
from typing import Any

from homebot.cli.options import add_world_options, load_world
from homebot.cli.ros_options import add_transport_options, transport_node
from homebot.cli.simulated import record_final_state
from homebot.scenarios import SimulatedRun, disturbance_level, disturbed
from homebot.scenarios.embodied import add_fidelity_option

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
    serve.set_defaults(handler=_serve)
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)


def _serve(args: argparse.Namespace) -> int:
    node = transport_node(args)
    from homebot.transport.sim_server import SimServer

    world = load_world(args)
    run = SimulatedRun.create(world, seed=args.seed, fidelity=args.fidelity,
                              disturbances=disturbed(args.disturb) if args.disturb else None)
    server = SimServer(node, run.robot, world, run.simulation.events,
                       final_state=lambda: record_final_state(run))
    print(f"homebot sim serve: {world.name}, seed {args.seed}, ROS 2 domain {args.domain_id} "
          f"on {args.interface}", flush=True)
    try:
        while True:
            server.spin_once(0.2)
    except KeyboardInterrupt:
        return 0
