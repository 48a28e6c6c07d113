"""Options of the ROS 2 commands: domain id, network interface, mapping file."""

from __future__ import annotations

import argparse
import logging
import os
from typing import TYPE_CHECKING

from homebot.errors import HomebotError
from homebot.transport import require_ros

if TYPE_CHECKING:
    from homebot.transport.node import Node

__all__ = ["SERVER_KEEP", "add_transport_options", "serve_logging", "transport_node"]

#: Events (and trail points) a server keeps in memory: a server runs for days.
SERVER_KEEP = 5000


def _domain_id(text: str) -> int:
    if not text.isdigit() or int(text) > 232:
        raise argparse.ArgumentTypeError(f"a ROS_DOMAIN_ID from 0 to 232, not '{text}'")
    return int(text)


def add_transport_options(parser: argparse.ArgumentParser) -> None:
    """``--domain-id N`` (default $ROS_DOMAIN_ID or 0) and ``--interface NAME`` (default lo)."""
    default = os.environ.get("ROS_DOMAIN_ID", "0")
    parser.add_argument("--domain-id", type=_domain_id,
                        default=_domain_id(default) if default.isdigit() else 0,
                        help="the DDS domain (default: $ROS_DOMAIN_ID or 0)")
    parser.add_argument("--interface", default="lo",
                        help="network interface (default lo: this machine only; a real robot's "
                             "network: its interface, e.g. eth0)")


def transport_node(args: argparse.Namespace) -> Node:
    """A ROS 2 node on the domain and interface the options name."""
    require_ros()
    from homebot.transport.node import Node, TransportSettings, loopback

    settings = loopback(args.domain_id) if args.interface == "lo" else \
        TransportSettings(args.domain_id, interface=args.interface)
    try:
        return Node(settings)
    except HomebotError:
        raise


def serve_logging() -> None:
    """A server's log: one line on stderr per refused request (``homebot.transport``)."""
    logging.basicConfig(format="%(name)s: %(levelname)s: %(message)s", level=logging.WARNING)
