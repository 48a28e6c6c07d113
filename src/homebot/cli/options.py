"""Options shared by command groups: the world, the seed, the fidelity, retry budgets,
the time limit, disturbances and probabilities."""

from __future__ import annotations

import argparse
import ipaddress
import math
import re
import socket
from collections.abc import Callable

from homebot import seeds
from homebot.app import Fidelity
from homebot.errors import HomebotError, TaskError
from homebot.skills import SKILLS
from homebot.world import World

__all__ = [
    "GPSR_TIME_LIMIT",
    "add_fidelity_option",
    "add_retry_option",
    "add_time_limit_option",
    "add_world_options",
    "disturbance_level",
    "fidelity_of",
    "listening_address",
    "load_world",
    "probability",
    "retry_budgets",
    "time_limit",
    "wait_seconds",
    "walker_count",
    "whole_number",
]

GPSR_TIME_LIMIT = 300.0  #: seconds: the competition's 5 minutes for a GPSR command


def add_world_options(parser: argparse.ArgumentParser) -> None:
    """``--world W`` and ``--seed N``, wherever a world is used."""
    parser.add_argument("--world", default="apartment",
                        help="world file, or a shipped world name (default: apartment)")
    parser.add_argument("--seed", type=seeds.seed, default=0, help="seed for every random choice")


def load_world(args: argparse.Namespace) -> World:
    """The world named by ``--world``."""
    try:
        return World.load(args.world)
    except HomebotError:
        raise
    except (OSError, ValueError) as error:  # pragma: no cover - mapped for safety
        raise HomebotError(f"cannot load world '{args.world}': {error}") from None


def add_retry_option(parser: argparse.ArgumentParser) -> None:
    """``--retries SKILL=N,...``: retry budgets per skill for this run."""
    parser.add_argument("--retries", default="", metavar="SKILL=N,...",
                        help="extra attempts per skill, e.g. pick=4,navigate=0 "
                             "(default: each skill's own budget)")


def retry_budgets(text: str) -> dict[str, int]:
    """Parse ``pick=4,navigate=0``; an unknown skill or a bad count raises ``TaskError``."""
    budgets: dict[str, int] = {}
    for item in filter(None, (part.strip() for part in text.split(","))):
        skill, equals, count = item.partition("=")
        skill = skill.strip()
        if skill not in SKILLS:
            raise TaskError(f"--retries: unknown skill '{skill}'; skills: {', '.join(SKILLS)}")
        if not equals or not count.strip().isdigit() or int(count) > 100:
            raise TaskError(f"--retries: '{item}' needs a count from 0 to 100, e.g. {skill}=3")
        budgets[skill] = int(count)
    return budgets


def add_time_limit_option(parser: argparse.ArgumentParser, default: float | None) -> None:
    """``--time-limit T``: the task's budget in simulated time (``300``, ``90s``, ``5m``, ``none``).

    For every command that runs a task (``run-task``, ``do``, and a conversation's
    commands); ``default`` is None for no limit.
    """
    shown = "none" if default is None else f"{default:g} s"
    parser.add_argument("--time-limit", type=time_limit, default=default, metavar="T",
                        help="the task's budget in simulated time: seconds, or with s/m/h "
                             f"(90s, 5m), or none (default: {shown}); searches stop at it")


_DURATION = re.compile(r"\s*(\d+(?:\.\d*)?|\.\d+)\s*(s|sec|m|min|h)?\s*", re.IGNORECASE)
_UNIT = {"": 1.0, "s": 1.0, "sec": 1.0, "m": 60.0, "min": 60.0, "h": 3600.0}


def time_limit(text: str) -> float | None:
    """Parse ``--time-limit``: ``300``, ``90s``, ``5m``, ``1h`` or ``none`` (no limit)."""
    if text.strip().lower() in {"none", "off", "no"}:
        return None
    match = _DURATION.fullmatch(text)
    seconds = float(match.group(1)) * _UNIT[(match.group(2) or "").lower()] if match else math.nan
    if not match or not 0 < seconds <= 86_400:
        raise argparse.ArgumentTypeError(
            f"'{text}' is not a time limit; give simulated seconds above 0 and at most a day "
            "(300, 90s, 5m) or none")
    return seconds


def add_fidelity_option(parser: argparse.ArgumentParser) -> None:
    """``--fidelity symbolic|embodied``."""
    parser.add_argument("--fidelity", type=Fidelity, choices=list(Fidelity),
                        default=Fidelity.SYMBOLIC,
                        help="symbolic (fast, the default) or embodied (the robot localises "
                             "from its laser and drives with the reactive planner)")


def fidelity_of(args: argparse.Namespace) -> Fidelity:
    """The ``--fidelity`` asked for (symbolic when the arguments have none)."""
    return Fidelity(getattr(args, "fidelity", Fidelity.SYMBOLIC))


def disturbance_level(text: str) -> float:
    """An argparse type: a level for ``homebot.app.disturbed``, 0 (none) to 6 (90 % of
    grasps slip)."""
    return _number_between(text, 0.0, 6.0, "a disturbance level")


def probability(text: str) -> float:
    """An argparse type: a probability, 0 to 1."""
    return _number_between(text, 0.0, 1.0, "a probability")


def wait_seconds(text: str) -> float:
    """An argparse type: wall-clock seconds to wait for something, above 0 and at most an
    hour (``--connect-timeout``)."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0.0 < value <= 3600.0:  # also false for nan
        raise argparse.ArgumentTypeError(f"a time to wait is more than 0 seconds and at most "
                                         f"3600, not '{text}'")
    return value


def walker_count(text: str) -> int:
    """An argparse type for ``--walkers``: how many people walk about, 0 to 50."""
    if not text.isdigit() or int(text) > 50:
        raise argparse.ArgumentTypeError(f"a count of people from 0 to 50, not '{text}'")
    return int(text)


def whole_number(low: int, high: int) -> Callable[[str], int]:
    """An argparse type: a whole number from ``low`` to ``high`` (``--crash-after``)."""
    def whole(text: str) -> int:
        stripped = text.strip()
        if not stripped.lstrip("-").isdigit() or not low <= int(stripped) <= high:
            raise argparse.ArgumentTypeError(f"a whole number from {low} to {high}, "
                                             f"not '{text}'")
        return int(stripped)
    whole.__name__ = "whole number"  # argparse names the type in its own messages
    return whole


_DOTTED_NUMBERS = re.compile(r"[\d.]+")


def listening_address(text: str) -> str:
    """An argparse type for ``--host``: an address of this machine a server can listen on.

    An IP address (``127.0.0.1``, ``0.0.0.0``, ``::1``) or a host name that resolves to
    one; the address is bound once, on a free port, so one that belongs to another
    machine (or none, as ``999.1.1.1``) is refused here, naming the option, and not by
    the server later.
    """
    fix = ("give 127.0.0.1 (this machine only), 0.0.0.0 (every network interface) or an "
           "address of this machine")
    try:
        address = str(ipaddress.ip_address(text.strip()))
    except ValueError:
        if _DOTTED_NUMBERS.fullmatch(text.strip()) or not text.strip():
            raise argparse.ArgumentTypeError(f"'{text}' is no IP address; {fix}") from None
        try:
            address = str(socket.getaddrinfo(text.strip(), None, type=socket.SOCK_STREAM)[0][4][0])
        except (OSError, UnicodeError) as error:
            raise argparse.ArgumentTypeError(f"'{text}' is no host name this machine can "
                                             f"resolve ({error}); {fix}") from None
    family = socket.AF_INET6 if ":" in address else socket.AF_INET
    try:
        with socket.socket(family, socket.SOCK_STREAM) as probe:
            probe.bind((address, 0))
    except OSError as error:
        raise argparse.ArgumentTypeError(f"'{text}' is not an address of this machine "
                                         f"({error.strerror or error}); {fix}") from None
    return text.strip()


def _number_between(text: str, low: float, high: float, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not low <= value <= high:  # also false for nan
        raise argparse.ArgumentTypeError(f"{what} is a number from {low:g} to {high:g}, "
                                         f"not '{text}'")
    return value
