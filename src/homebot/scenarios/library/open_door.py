"""Opening and closing a door under compliance (Cosero §4.2).

The robot stands before a seeded door (hinged left or right, 0.7–0.95 m wide, with hinge
friction and damping) that opens towards it. It looks at the door from 1.2 m before it and
finds the leaf, the bar handle and the hinge in the head camera's depth points
(``homebot.perception.door_leaf``; the hinge it finds is centimetres off); it steps up to
the handle, grasps it, pulls the door round the hinge until it believes it is open by 69°,
holds it a moment, and pushes it shut again, then lets go. The hand is compliant in the
plane and in yaw, and its target is set every tick from where the hand actually is, so the
door's true circle prevails over the robot's estimate. Success is the truth: the hinge truly
opened at least 60°, ended within 2° of shut, the handle never left the fingers and the
robot's body never touched the door or its frame.
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
    """Open the door and close it again."""
    from homebot.trials.interaction import door_episode

    result = door_episode(args.seed, 0)
    door = result.variant
    speech = ["I will open the door.",
              "The door is open, and shut again." if result.success else
              "I could not open and close the door properly."]
    if console is not None:
        if not result.perceived:
            console.print("no door with a handle was seen before the robot")
        console.print(f"a door {door.width:.2f} m wide hinged on the {door.side} "
                      f"(hinge friction {door.friction:.1f} N·m): opened to "
                      f"{result.opened_deg:.1f}°, closed to {result.closed_deg:.1f}°"
                      f"{'; the handle slipped from the fingers' if result.lost_handle else ''}"
                      f"{'; the robot bumped the door' if result.bumped else ''}")
        console.print(speech[-1])
    actions = [{"skill": "open", "args": {"door": "door"},
                "status": "verified" if result.open_s is not None and
                result.opened_deg >= 60.0 else "aborted"},
               {"skill": "close", "args": {"door": "door"},
                "status": "verified" if result.success else "aborted"}]
    return scenario_summary("open_door", result.success, actions, speech,
                            side=door.side, width_m=round(door.width, 3),
                            hinge_friction_nm=round(door.friction, 2),
                            perceived=result.perceived, hinge_error_m=result.hinge_error,
                            opened_deg=result.opened_deg, closed_deg=result.closed_deg,
                            lost_handle=result.lost_handle, bumped=bool(result.bumped),
                            open_s=result.open_s, close_s=result.close_s)
