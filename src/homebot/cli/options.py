"""Options shared by command groups: the world, the seed, the fidelity, retry budgets,
the time limit, disturbances and probabilities."""

from __future__ import annotations

import argparse
import math
import re

from homebot.app import Fidelity
from homebot.errors import HomebotError, TaskError
from homebot.skills import SKILLS
from homebot.world import World

__all__ = ["GPSR_TIME_LIMIT", "add_fidelity_option", "add_retry_option", "add_time_limit_option",
           "add_world_options", "disturbance_level", "fidelity_of", "load_world", "probability",
           "retry_budgets", "time_limit"]

GPSR_TIME_LIMIT = 300.0  #: seconds: the competition's 5 minutes for a GPSR command


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


def _number_between(text: str, low: float, high: float, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not low <= value <= high:  # also false for nan
        raise argparse.ArgumentTypeError(f"{what} is a number from {low:g} to {high:g}, "
                                         f"not '{text}'")
    return value
