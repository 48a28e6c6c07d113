"""Follow Me (RoboCup@Home, Cosero §8.2), in the embodied fidelity, judged by the truth.

Each run is one seeded episode of ``homebot.trials.following``: the operator walks 15–25 m
through the home with two passers-by crossing, then says "stop"; the robot follows by
tracking, told only where it starts. A run succeeds when, by the simulator's truth, the
robot stayed within 3 m of the operator throughout, stopped within 5 s of "stop" and stood
still, and touched nobody and nothing. Runs go over ``--worlds`` in turn, seeds from
``--seed`` on.
"""

from __future__ import annotations

import argparse
import statistics
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.app.embodied import follow_me_episode
from homebot.bench.arguments import count, seed
from homebot.navigation import Navigator
from homebot.progress import track
from homebot.world import World

__all__ = ["add_arguments", "run"]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--runs", type=count("--runs", 1, 10_000), default=50,
                        help="Follow Me episodes (default 50)")
    parser.add_argument("--seed", type=seed, default=1, help="the first episode's seed")
    parser.add_argument("--worlds", nargs="+", default=["apartment", "family_home"],
                        help="world files or shipped names, taken in turn")


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    worlds = [World.load(name) for name in args.worlds]
    navigators = [Navigator(world) for world in worlds]
    episodes = []
    for index in track(range(args.runs), "Follow Me episodes"):
        which = index % len(worlds)
        episode = follow_me_episode(worlds[which], args.seed + index, navigators[which])
        episodes.append(episode.to_dict())
        if console is not None:
            verdict = "skipped" if episode.skipped else (
                "ok" if episode.success else f"FAIL ({_why(episode.to_dict())})")
            console.print(f"  {episode.world} seed {episode.seed}: {verdict}, "
                          f"max gap {episode.max_gap} m, {episode.wall_seconds} s")
    figures = _figures(episodes)
    if console is not None:
        table = Table(title=f"Follow Me, {args.runs} runs ({', '.join(args.worlds)})")
        for column in ("succeeded", "within 3 m", "stopped on 'stop'", "collisions",
                       "median max gap", "lost and found again", "speed x real time"):
            table.add_column(column)
        table.add_row(f"{figures['succeeded']}/{figures['ran']}",
                      str(figures["kept_within"]), str(figures["stopped"]),
                      str(figures["collisions"]), f"{figures['median_max_gap_m']} m",
                      str(figures["lost_and_found"]), f"{figures['speed_x_real_time']}x")
        console.print(table)
    return {"benchmark": "follow", "runs": args.runs, "seed": args.seed,
            "worlds": args.worlds, **figures, "episodes": episodes}


def _why(episode: dict[str, Any]) -> str:
    reasons = []
    if not episode["kept_within"]:
        reasons.append("fell behind")
    if not episode["stopped"]:
        reasons.append(f"did not stop on 'stop' (ended: {episode['end']})")
    if episode["collisions"]:
        reasons.append("collided")
    return ", ".join(reasons)


def _figures(episodes: list[dict[str, Any]]) -> dict[str, Any]:
    ran = [e for e in episodes if not e["skipped"]]
    succeeded = sum(e["success"] for e in ran)
    wall = sum(e["wall_seconds"] for e in ran)
    return {
        "succeeded": succeeded,
        "ran": len(ran),
        "skipped_runs": len(episodes) - len(ran),  # no arena of the length in the home
        "success_rate": round(succeeded / len(ran), 3) if ran else None,
        "kept_within": sum(e["kept_within"] for e in ran),
        "stopped": sum(e["stopped"] for e in ran),
        "collisions": sum(len(e["collisions"]) for e in ran),
        "median_max_gap_m": round(statistics.median(e["max_gap"] for e in ran), 2)
        if ran else None,
        "lost_and_found": sum(e["lost"] for e in ran),
        "ends": {end: sum(e["end"] == end for e in ran) for end in sorted({e["end"]
                                                                           for e in ran})},
        "speed_x_real_time": round(sum(e["sim_seconds"] for e in ran) / wall, 1)
        if wall else None,
        "targets": {"success_rate": 0.9, "collisions": 0},
    }
