"""``homebot serve``: the web console over one simulated home (needs the ``web`` extra)."""

from __future__ import annotations

import argparse
import importlib.util
import secrets
import socket
from typing import Any

from homebot.app import Fidelity, require_embodied
from homebot.cli.options import (
    add_fidelity_option,
    add_world_options,
    listening_address,
    load_world,
    walker_count,
)
from homebot.errors import HomebotError

__all__ = ["register", "serve"]

_WS_MAX_MESSAGE = 4096  #: bytes of one message a client may send on the websocket


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("serve", help="watch and command the robot in a browser")
    add_world_options(parser)
    add_fidelity_option(parser)
    parser.add_argument("--host", type=listening_address, default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this machine only)")
    parser.add_argument("--port", type=_port, default=8765, help="port (default 8765)")
    parser.add_argument("--speed", type=_speed, default=1.0, metavar="X",
                        help="real-time factor of the simulated home: 1, 5, ... "
                             "or 0 for as fast as possible (default 1)")
    parser.add_argument("--token", default=None,
                        help="the access token (default: a new random one, printed)")
    parser.add_argument("--walkers", type=walker_count, default=0, metavar="N",
                        help="embodied: how many people walk about on their own")
    parser.add_argument("--lease", type=_lease, default=10.0, metavar="SECONDS",
                        help="control lapses this many seconds after the operator's page "
                             "stops renewing it (closed, reloaded, offline; default 10)")
    parser.set_defaults(handler=serve)


def _port(text: str) -> int:
    if not text.isdigit() or not 1 <= int(text) <= 65535:
        raise argparse.ArgumentTypeError(f"a port from 1 to 65535, not '{text}'")
    return int(text)


def _speed(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0.0 <= value <= 1000.0:
        raise argparse.ArgumentTypeError(f"a real-time factor from 0 (as fast as possible) "
                                         f"to 1000, not '{text}'")
    return value


def _lease(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 1.0 <= value <= 3600.0:
        raise argparse.ArgumentTypeError(f"seconds from 1 to 3600, not '{text}'")
    return value


def _check_port(host: str, port: int) -> None:
    """Refuse a port this machine cannot listen on (one in use), naming the option, before
    the home is built (``--host`` was checked as it was read)."""
    try:
        family = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
        with socket.socket(family[0], socket.SOCK_STREAM) as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            probe.bind(family[4])
    except (OSError, UnicodeError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise HomebotError(f"--port {port}: cannot listen there on {host} ({reason}); give "
                           "a free port") from None


def serve(args: argparse.Namespace) -> int:
    """Run the console until interrupted."""
    if importlib.util.find_spec("fastapi") is None or importlib.util.find_spec("uvicorn") is None:
        raise HomebotError("homebot serve needs the 'web' extra: pip install 'homebot[web]'")
    if args.fidelity is Fidelity.EMBODIED:
        require_embodied()
    if args.token is not None and len(args.token) < 8:
        raise HomebotError("--token: give at least 8 characters (or leave it out for a "
                           "random one)")
    _check_port(args.host, args.port)
    import uvicorn

    from homebot.web import ConsoleSettings
    from homebot.web.app import create_app

    token = args.token or secrets.token_urlsafe(16)
    settings = ConsoleSettings(world=load_world(args), token=token, seed=args.seed,
                               fidelity=args.fidelity, speed=args.speed, walkers=args.walkers,
                               lease=args.lease)
    app = create_app(settings)
    print(f"homebot console: http://{args.host}:{args.port}/?token={token}", flush=True)
    # the page never sends on its websocket: a client that does gets little buffered
    uvicorn.run(app, host=args.host, port=args.port, log_level="warning",
                ws_max_size=_WS_MAX_MESSAGE, ws_max_queue=4)
    return 0
