"""Handing an object over (Cosero §7.3.1): the robot lets go when the person pulls, not before.

The robot holds a bottle out, compliant forward, upward and in pitch. A seeded person
bumps it lightly (below the pull threshold) and then pulls. Success is the physics'
truth: the bottle left the fingers within 0.5 s of the pull's exceeding the threshold,
and not before.
"""

from __future__ import annotations

import argparse
from typing import Any

from rich.console import Console

from homebot.scenarios.running import RunBuilder
from homebot.scenarios.summary import scenario_summary

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    del parser  # --seed and --json only


def run(args: argparse.Namespace, console: Console | None, build: RunBuilder) -> dict[str, Any]:
    """Hold the bottle out until the person pulls."""
    from homebot.trials.interaction import HANDOVER_THRESHOLD, handover_episode

    result = handover_episode(args.seed, 0, pull=True)
    speech = ["Here is your bottle.", "You have it." if result.correct else
              "I did not let go when you pulled." if result.left_hand_at is None else
              "The bottle left my hand at the wrong moment."]
    if console is not None:
        console.print(f"the person bumped the bottle {result.bumps} time(s) below "
                      f"{HANDOVER_THRESHOLD:g} N, then pulled: above the threshold at "
                      f"{_seconds(result.pull_above)}, released at "
                      f"{_seconds(result.decided_at)}, out of the fingers at "
                      f"{_seconds(result.left_hand_at)}")
        console.print(speech[-1])
    actions = [{"skill": "give", "args": {"object": "bottle"},
                "status": "verified" if result.correct else "aborted"}]
    delay = result.delay
    return scenario_summary("handover", result.correct, actions, speech,
                            bumps=result.bumps, pull_above_s=result.pull_above,
                            released_s=result.decided_at, left_hand_s=result.left_hand_at,
                            delay_s=None if delay is None else round(delay, 3))


def _seconds(value: float | None) -> str:
    return "never" if value is None else f"{value:.2f} s"
