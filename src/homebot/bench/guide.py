"""Guiding (RoboCup@Home; Cosero §8.2), in the embodied fidelity, judged by the truth.

Each run is one seeded episode of ``homebot.trials.guiding``: the robot asks someone to
follow it to a piece of furniture 6–20 m away through doors, and leads them with its
Guide skill, tracking them as it goes; the person follows by their own rule, and by seed
lags or wanders off. A run succeeds when, by the simulator's truth, the person ends
within 1.5 m of the goal within the time limit and the robot touched nobody and nothing.
Runs go over ``--world`` in turn, seeds from ``--seed`` on.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.app.guiding import guide_episode
from homebot.bench.arguments import count, seed
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--runs", type=count("--runs", 1, 10_000), default=50,
                        help="guiding episodes (default 50)")
    parser.add_argument("--seed", type=seed, default=1, help="the first episode's seed")
    parser.add_argument("--world", nargs="+", default=["apartment", "family_home"],
                        help="world files or shipped names, taken in turn")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    began = time.perf_counter()
    worlds = [World.load(name) for name in args.world]
    navigators = [Navigator(world) for world in worlds]
    episodes = []
    for index in track(range(args.runs), "guiding episodes"):
        which = index % len(worlds)
        episode = guide_episode(worlds[which], args.seed + index, navigators[which]).to_dict()
        episodes.append(episode)
        if console is not None:
            console.print(f"  {episode['world']} seed {episode['seed']}: {_line(episode)}")
    figures = _figures(episodes)
    figures["wall_seconds"] = round(time.perf_counter() - began, 1)
    if console is not None:
        table = Table(title=f"Guide, {args.runs} runs ({', '.join(args.world)})")
        for column in ("succeeded", "wandered off", "noticed lost", "fetched", "waited",
                       "collisions", "robot said verified, truth failed", "sim s", "wall s"):
            table.add_column(column)
        table.add_row(f"{figures['succeeded']}/{figures['ran']}", str(figures["wandered_off"]),
                      str(figures["noticed_lost"]), str(figures["fetched"]),
                      str(figures["waited"]), str(figures["collisions"]),
                      str(figures["false_verified"]), str(figures["sim_seconds"]),
                      str(figures["wall_seconds"]))
        console.print(table)
    return {"benchmark": "guide", "runs": args.runs, "seed": args.seed,
            "worlds": args.world, **figures, "episodes": episodes}


def _line(episode: dict[str, Any]) -> str:
    if episode["skipped"]:
        return f"skipped ({episode['skipped']})"
    verdict = "ok" if episode["success"] else "FAIL"
    return (f"{verdict}: {episode['person']} ({episode['personality']}) to the "
            f"{episode['goal']}, {episode['route_length']} m, ended "
            f"{episode['end_distance']} m from it, robot {episode['robot_verdict']}, "
            f"{len(episode['collisions'])} collisions, {episode['sim_seconds']} sim s, "
            f"{episode['wall_seconds']} s")


def _figures(episodes: list[dict[str, Any]]) -> dict[str, Any]:
    ran = [e for e in episodes if not e["skipped"]]
    succeeded = sum(e["success"] for e in ran)
    by_personality = {
        kind: f"{sum(e['success'] for e in ran if e['personality'] == kind)}/"
              f"{sum(e['personality'] == kind for e in ran)}"
        for kind in sorted({e["personality"] for e in ran})}
    return {
        "succeeded": succeeded,
        "ran": len(ran),
        "skipped_runs": len(episodes) - len(ran),
        "success_rate": round(succeeded / len(ran), 3) if ran else None,
        "by_personality": by_personality,
        "at_goal_any_time": sum(e["at_goal"] for e in ran),
        "over_time": sum(e["at_goal"] and not e["in_time"] for e in ran),
        "wandered_off": sum(e["wandered_off"] for e in ran),
        "noticed_lost": sum(e["noticed"] for e in ran),
        "fetched": sum(e["fetched"] for e in ran),
        "waited": sum(e["waited"] for e in ran),
        "collisions": sum(len(e["collisions"]) for e in ran),
        "person_collisions": sum(e["person_collisions"] for e in ran),
        "false_verified": sum(e["robot_verdict"] == "verified" and not e["success"]
                              for e in ran),
        "sim_seconds": round(sum(e["sim_seconds"] for e in ran), 1),
        "targets": {"success_rate": 0.9, "collisions": 0},
    }
