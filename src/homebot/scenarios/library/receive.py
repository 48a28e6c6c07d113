"""Taking an object from a person (Cosero §7.3.1): offer the open hand, close on what is put in.

The robot holds its open hand out. A seeded person brings a bottle, pushes it between
the fingers until it touches the palm, and lets go once the fingers hold it. The robot
feels the touch at its wrist, closes, and checks that something is between the fingers
and that it carries its weight. Success is the physics' truth: at the end both fingers
touch the bottle and it hangs in the hand, and the robot believes it holds it.
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
    """Hold the hand out and take the bottle."""
    from homebot.trials.interaction import receive_episode

    result = receive_episode(args.seed)
    speech = ["Please put the bottle in my hand.",
              "Thank you, I have it." if result.success else "I did not get it."]
    if console is not None:
        closed = "never" if result.closed_at is None else f"{result.closed_at:.2f} s"
        let_go = "never" if result.let_go_at is None else f"{result.let_go_at:.2f} s"
        console.print(f"the hand closed at {closed}, the person let go at {let_go}; the "
                      f"robot ends {result.phase}, and the bottle "
                      f"{'is' if result.held else 'is not'} in its hand")
        console.print(speech[-1])
    actions = [{"skill": "receive", "args": {"object": "bottle"},
                "status": "verified" if result.success else "aborted"}]
    return scenario_summary("receive", result.success, actions, speech, phase=result.phase,
                            closed_s=result.closed_at, let_go_s=result.let_go_at,
                            held=result.held)
