"""Options shared by command groups: the world, the seed, disturbances."""

from __future__ import annotations

import argparse

from homebot.errors import HomebotError
from homebot.world import World

__all__ = ["add_world_options", "load_world"]


def add_world_options(parser: argparse.ArgumentParser) -> None:
    """``--world W`` and ``--seed N``, wherever a world is used."""
    parser.add_argument("--world", default="apartment",
                        help="world file, or a shipped world name (default: apartment)")
    parser.add_argument("--seed", type=int, default=0, help="seed for every random choice")


def load_world(args: argparse.Namespace) -> World:
    """The world named by ``--world``."""
    try:
        return World.load(args.world)
    except HomebotError:
        raise
    except (OSError, ValueError) as error:  # pragma: no cover - mapped for safety
        raise HomebotError(f"cannot load world '{args.world}': {error}") from None
