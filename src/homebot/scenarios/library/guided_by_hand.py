"""Being guided by the hand (Cosero §7.3.2): follow where a person leads, through the home.

A person takes the robot's outstretched hand and walks a seeded route through the
apartment (3–8 m, keeping 0.5 m from walls and furniture). The hand is compliant in
the plane; the base drives in the hand's footsteps. Success is the truth: the base's
median distance from the person's path is at most 10 cm, its footprint never overlaps
a wall or furniture, and it ends with its hand where the person stopped.
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
    """Follow the person's hand along their route."""
    from homebot.trials.interaction import guided_episode

    result = guided_episode(args.seed, 0)
    median = result.median_deviation
    success = median <= 0.10 and result.collisions == 0 and result.arrived
    speech = ["Lead the way.", "We are there." if success else "I could not follow you well."]
    if console is not None:
        console.print(f"led {result.route_length:.2f} m: the base kept a median "
                      f"{median * 100:.1f} cm (worst {max(result.deviations) * 100:.1f} cm) "
                      f"from the person's path, {result.collisions} tick(s) touching, and "
                      f"{'arrived' if result.arrived else 'did not arrive'}")
        console.print(speech[-1])
    actions = [{"skill": "follow", "args": {"person": "operator", "by": "hand"},
                "status": "verified" if success else "aborted"}]
    return scenario_summary("guided_by_hand", success, actions, speech,
                            route_m=round(result.route_length, 2),
                            median_deviation_m=round(median, 4),
                            max_deviation_m=round(max(result.deviations), 4),
                            collisions=result.collisions, arrived=result.arrived)
