"""``homebot run-task FILE``: run a YAML task of skill steps in the simulated home."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from homebot.cli.options import load_world
from homebot.cli.ros_run import add_ros_robot_options, run_over_ros
from homebot.cli.simulated import add_run_options, finish_run, showing_steps, simulated_run
from homebot.executive.taskfile import load_task

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("run-task", help="run a YAML task of skill steps")
    parser.add_argument("file", type=Path, help="task file: a list of {skill: NAME, ARG: VALUE}")
    add_run_options(parser)
    parser.add_argument("--no-monitoring", action="store_true",
                        help="run as a plain sequence: no monitoring, retries or recovery")
    add_ros_robot_options(parser)
    parser.set_defaults(handler=run_task)


def run_task(args: argparse.Namespace) -> int:
    world = load_world(args)
    task = load_task(args.file, world)
    if args.robot == "ros":
        return run_over_ros(args, world, task, monitoring=not args.no_monitoring)
    run = simulated_run(args, world, monitoring=not args.no_monitoring)
    with showing_steps(run):
        report = run.run(task)
    return finish_run(args, run, report)
