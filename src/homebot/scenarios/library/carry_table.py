"""Carrying a table with a person (Cosero §7.3.3): lift, walk and lower together, level.

The robot holds the handle at one end of a table; a seeded person takes the other end,
lifts it, walks 1.5–3 m with it and puts it down. The robot waits until it sees the
table pitch by 0.02 rad, then keeps it level while following the person's pulls and
pushes, and lowers when the person does. Success is the truth: the table stayed within
3° of level while off the floor, it travelled more than a metre, the robot's fingers
never lost the handle, and the table stands on its legs at the end.
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
    """Carry the table with the person."""
    from homebot.trials.interaction import carry_table_episode

    result = carry_table_episode(args.seed, 0)
    speech = ["I have my end of the table.",
              "The table is down." if result.success else "We did not carry the table well."]
    if console is not None:
        lifted = "never" if result.lifted_at is None else \
            f"{result.lifted_at:.2f} s after the person began"
        console.print(f"lifted {lifted}; carried {result.travelled:.2f} m at up to "
                      f"{result.max_height:.2f} m, tilted at most {result.max_tilt_deg:.2f}°"
                      f"{'; the handle slipped from the fingers' if result.dropped else ''}; "
                      f"{'lowered' if result.lowered else 'not lowered'}")
        console.print(speech[-1])
    actions = [{"skill": "carry", "args": {"object": "table", "with": "operator"},
                "status": "verified" if result.success else "aborted"}]
    return scenario_summary("carry_table", result.success, actions, speech,
                            lifted_after_s=result.lifted_at, max_tilt_deg=result.max_tilt_deg,
                            max_height_m=float(result.max_height), travelled_m=result.travelled,
                            dropped=result.dropped, lowered=bool(result.lowered))
