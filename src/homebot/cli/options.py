"""Options shared by command groups: the world, the seed, retry budgets."""

from __future__ import annotations

import argparse

from homebot.errors import HomebotError, TaskError
from homebot.skills import SKILLS
from homebot.world import World

__all__ = ["add_retry_option", "add_world_options", "load_world", "retry_budgets"]


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
