"""``homebot ros serve``: homebot as a ROS 2 node (command action, parse, events, speech)."""

from __future__ import annotations

import argparse
from typing import Any

from homebot.cli.options import GPSR_TIME_LIMIT, load_world
from homebot.cli.ros_options import (
    SERVER_KEEP,
    add_transport_options,
    serve_logging,
    transport_node,
)
from homebot.cli.simulated import add_run_options, simulated_run
from homebot.language import Vocabulary, parse_command

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("ros", help="offer homebot to a ROS 2 system")
    commands = parser.add_subparsers(dest="ros_command", metavar="COMMAND")
    serve = commands.add_parser(
        "serve", help="serve /homebot/command (action), /homebot/parse (service), "
                      "/homebot/events and /homebot/speech (topics) until stopped")
    add_run_options(serve, time_limit=GPSR_TIME_LIMIT)
    add_transport_options(serve)
    serve.set_defaults(handler=_serve)
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)


def _serve(args: argparse.Namespace) -> int:
    serve_logging()
    node = transport_node(args)
    from homebot.transport.command_server import CommandOutcome, CommandServer

    world = load_world(args)
    vocabulary = Vocabulary.from_world(world)
    run = simulated_run(args, world)  # one home that persists from command to command
    run.simulation.events.keep = run.simulation.trail_keep = SERVER_KEEP

    def carry_out(command: str) -> CommandOutcome:
        parsed = parse_command(command, vocabulary)
        if not parsed:
            said = parsed.question or parsed.reason or "I did not understand."
            run.simulation.events.record("speech", text=said)
            return CommandOutcome(False, (said,), "not_understood")
        report = run.run(parsed.to_task())
        return CommandOutcome(report.success, tuple(report.speech), report.reason)

    server = CommandServer(node, parse=lambda text: parse_command(text, vocabulary).to_dict(),
                           carry_out=carry_out, events=run.simulation.events)
    print(f"homebot ros serve: {world.name}, seed {args.seed}, ROS 2 domain {args.domain_id} "
          f"on {args.interface}", flush=True)
    try:
        while True:
            server.spin_once(0.2)
    except KeyboardInterrupt:
        return 0
