"""``run-task --robot ros``: the executive here, the robot on ROS 2 (``RosRobot``)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from rich.console import Console
from rich.markup import escape

from homebot.cli.options import retry_budgets, wait_seconds
from homebot.cli.ros_options import add_transport_options, transport_node
from homebot.cli.simulated import write_events
from homebot.errors import RobotLost
from homebot.executive import print_report
from homebot.task import Task
from homebot.world import World

__all__ = ["add_ros_robot_options", "run_over_ros"]


def add_ros_robot_options(parser: argparse.ArgumentParser) -> None:
    """``--robot sim|ros``, ``--mapping FILE``, ``--connect-timeout S`` and the transport's."""
    parser.add_argument("--robot", choices=("sim", "ros"), default="sim",
                        help="sim: the simulated home in this process (default); ros: a robot "
                             "on ROS 2 (homebot sim serve, or a real one named by --mapping)")
    parser.add_argument("--mapping", type=Path,
                        help="--robot ros: the mapping file of ROS 2 names (default: homebot's)")
    parser.add_argument("--connect-timeout", type=wait_seconds, default=20.0, metavar="S",
                        help="--robot ros: seconds (wall clock) to wait for the robot")
    add_transport_options(parser)


def run_over_ros(args: argparse.Namespace, world: World, task: Task, *,
                 monitoring: bool = True) -> int:
    """Run ``task`` on the ROS 2 robot; 0 when it succeeded, 1 when not or the robot was lost."""
    node = transport_node(args)
    from homebot.app.ros import RosRunSettings, build_ros_run

    run = build_ros_run(node, RosRunSettings(
        world=world, mapping=args.mapping, connect_timeout=args.connect_timeout,
        monitoring=monitoring, retries=retry_budgets(args.retries), time_limit=args.time_limit))
    events = run.events
    console = Console()
    try:
        report = run.run(task)
    except RobotLost as error:
        message = ("I have lost contact with the robot, so I stopped the task; "
                   "please check the robot and start it again.")
        events.record("robot.lost", error=str(error))
        events.record("task.end", success=False, reason="robot_lost")
        if args.events:
            write_events(events, args.events)
        if args.json:
            print(json.dumps({"success": False, "reason": "robot_lost", "error": str(error),
                              "speech": [message]}))
        else:
            console.print(f"  [cyan]homebot:[/] {escape(message)}", highlight=False)
            console.print(f"  [red]failed[/]: {escape(str(error))}", highlight=False)
        return 1
    if args.events:
        write_events(events, args.events)
    if args.json:
        print(json.dumps(report.to_dict(), ensure_ascii=False))
    else:
        print_report(console, report)
    return 0 if report.success else 1
