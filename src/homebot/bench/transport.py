"""ROS 2 transport: throughput between two processes, fetch over ROS 2, a lost robot's detection.

- **throughput**: a publisher process sends ``sensor_msgs/LaserScan`` (271 beams) at
  ``--scan-rate`` per second and ``sensor_msgs/PointCloud2`` (320x240 points of x, y, z,
  rgb: 1.2 MB each) at ``--cloud-rate`` per second for ``--seconds`` seconds; this process
  receives. Reliable QoS keeping all samples; each process pinned to a core of its own
  (``os.sched_setaffinity``) where the machine has two. Lost = sent but never received.
- **fetch**: the fetch-and-deliver task with disturbances, for ``--seeds`` seeds, in-process
  and over ROS 2 (``homebot sim serve`` in another process); counts the seeds whose event
  logs are byte for byte the same and whose outcomes agree (the logs carry simulated time).
- **lost robot**: the simulator dies in the middle of the fetch (``--crash-after``, an
  abrupt exit as a kill would be); the wall-clock time until the task has ended with the
  operator told (DDS lease: 1 s).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import count
from homebot.progress import track
from homebot.transport import require_ros

__all__ = ["add_arguments", "publish", "run"]

_DOMAIN = 230  # the benchmark's own DDS domain, loopback only
_CLOUD = (320, 240, 16)  # width, height, point_step (x, y, z, rgb as float32)
_TASK = """\
description: bring the cola
steps:
  - {skill: navigate, to: fridge}
  - {skill: find_object, object: cola, placement: fridge}
  - {skill: pick, object: cola}
  - {skill: navigate, to: operator}
  - {skill: give, person: operator}
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--seconds", type=count("--seconds", 1, 600), default=5,
                        help="seconds of wall time per throughput stream")
    parser.add_argument("--scan-rate", type=count("--scan-rate", 1, 100_000), default=1000,
                        help="LaserScan messages per second")
    parser.add_argument("--cloud-rate", type=count("--cloud-rate", 1, 1000), default=30,
                        help="PointCloud2 (320x240) messages per second")
    parser.add_argument("--seeds", type=count("--seeds", 1, 1000), default=20,
                        help="seeds of the fetch task over ROS 2")
    parser.add_argument("--runs", type=count("--runs", 1, 1000), default=5,
                        help="seeded tracking drives, in-process and over ROS 2")
    parser.add_argument("--drive-seconds", type=count("--drive-seconds", 1, 3600), default=20,
                        help="simulated seconds per tracking drive")
    parser.add_argument("--only", choices=["all", "throughput", "fetch", "lost", "tracking"],
                        default="all", help="run one experiment only")


def _python(code: str, *arguments: str) -> list[str]:
    return [sys.executable, "-c", code, *arguments]


def _pin(core: int) -> None:
    if hasattr(os, "sched_setaffinity") and len(os.sched_getaffinity(0)) > 1:
        os.sched_setaffinity(0, {core % (os.cpu_count() or 1)})


def publish(kind: str, rate: int, seconds: int, domain_id: int) -> None:
    """The publisher process: ``rate`` messages per second of ``kind`` for ``seconds``."""
    from cyclonedds.core import GuardCondition, WaitSet

    from homebot.transport.naming import RELIABLE_ALL_QOS
    from homebot.transport.node import Node, loopback

    _pin(0)
    node = Node(loopback(domain_id))
    types = node.types
    if kind == "scan":
        topic, message = "/scan", types.new(
            "sensor_msgs/msg/LaserScan", angle_min=-2.356, angle_max=2.356,
            angle_increment=0.01745, range_min=0.05, range_max=10.0,
            ranges=[float(i % 97) / 10.0 for i in range(271)])
    else:
        width, height, step = _CLOUD
        fields = [types.new("sensor_msgs/msg/PointField", name=name, offset=4 * index,
                            datatype=7, count=1) for index, name in enumerate("xyz")]
        fields.append(types.new("sensor_msgs/msg/PointField", name="rgb", offset=12,
                                datatype=7, count=1))
        topic, message = "/camera/points", types.new(
            "sensor_msgs/msg/PointCloud2", height=height, width=width, fields=fields,
            point_step=step, row_step=step * width, data=bytes(step * width * height),
            is_dense=True)
    publisher = node.publisher(topic, message.__class__.__idl_typename__.replace(
        "::dds_::", "/").replace("::", "/").rstrip("_"), RELIABLE_ALL_QOS)
    if not publisher.wait_for_subscribers(1, 30.0):
        raise SystemExit("no subscriber")
    # Pacing waits on a DDS guard condition nobody triggers: a wait bounded by its timeout.
    pace = WaitSet(node.participant)
    pace.attach(GuardCondition(node.participant))
    total = rate * seconds
    began = time.perf_counter()
    for index in range(total):
        message.header.frame_id = str(index)
        ahead = began + index / rate - time.perf_counter()
        if ahead > 0:
            pace.wait(int(ahead * 1e9))
        publisher.publish(message)
    sent = time.perf_counter() - began
    for _ in range(100):  # until every reader has acknowledged (or 10 s)
        if _acknowledged(publisher.writer, int(1e8)):
            break
    print(f"{total} {sent:.3f}", flush=True)


def _acknowledged(writer: Any, nanoseconds: int) -> bool:
    try:
        return bool(writer.wait_for_acks(nanoseconds))
    except AttributeError:  # cyclonedds 11's wait_for_acks fails this way on a timeout
        return False


def _throughput(kind: str, rate: int, seconds: int) -> dict[str, Any]:
    from homebot.transport.naming import RELIABLE_ALL_QOS
    from homebot.transport.node import Node, loopback

    _pin(1)
    node = Node(loopback(_DOMAIN))
    topic, message = (("/scan", "sensor_msgs/msg/LaserScan") if kind == "scan"
                      else ("/camera/points", "sensor_msgs/msg/PointCloud2"))
    subscription = node.subscription(topic, message, RELIABLE_ALL_QOS)
    process = subprocess.Popen(
        _python("import sys; from homebot.bench.transport import publish; "
                "publish(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]))",
                kind, str(rate), str(seconds), str(_DOMAIN)), stdout=subprocess.PIPE, text=True)
    seen: set[int] = set()
    first = last = 0.0
    deadline = time.monotonic() + seconds * 3 + 30
    total = rate * seconds
    while len(seen) < total and time.monotonic() < deadline:
        samples = subscription.wait(0.5)
        if samples and not first:
            first = time.perf_counter()
        for sample in samples:
            seen.add(int(sample.header.frame_id))
        if samples:
            last = time.perf_counter()
        if not samples and process.poll() is not None and subscription.publishers() == 0:
            break
    output, _ = process.communicate(timeout=60)
    sent, sending = [*output.split(), "0", "0"][:2]
    received_time = last - first
    return {"messages": int(sent), "received": len(seen), "lost": total - len(seen),
            "sending_seconds": float(sending),
            "received_per_second": round(len(seen) / received_time, 1) if received_time else 0.0,
            "megabytes_per_second": round(len(seen) * _size(kind) / 1e6 / received_time, 1)
            if received_time else 0.0}


def _size(kind: str) -> int:
    width, height, step = _CLOUD
    return 271 * 4 + 80 if kind == "scan" else width * height * step + 120


def _fetch(seeds: int) -> dict[str, Any]:
    from homebot.cli import main

    same = agree = succeeded = 0
    different: list[dict[str, int]] = []
    with tempfile.TemporaryDirectory() as folder:
        task = Path(folder) / "task.yaml"
        task.write_text(_TASK, encoding="utf-8")
        for seed in track(range(seeds), "fetch over ROS 2"):
            domain_id = _DOMAIN - 1 - seed % 20
            here, there = Path(folder) / f"in{seed}.jsonl", Path(folder) / f"ros{seed}.jsonl"
            options = ["--seed", str(seed), "--disturb", "1"]
            with open(os.devnull, "w") as quiet:
                stdout, sys.stdout = sys.stdout, quiet
                try:
                    local = main(["run-task", str(task), "--events", str(here), *options])
                    server = _simulator(domain_id, options)
                    remote = main(["run-task", str(task), "--events", str(there), *options,
                                   "--robot", "ros", "--domain-id", str(domain_id)])
                finally:
                    sys.stdout = stdout
                    if "server" in locals():
                        server.kill()
                        server.wait(10)
            identical = here.exists() and there.exists() and \
                here.read_bytes() == there.read_bytes()
            same += identical
            agree += local == remote
            succeeded += remote == 0
            if not identical:
                different.append({"seed": seed, "in_process_status": local,
                                  "over_ros_status": remote})
    return {"seeds": seeds, "identical_event_logs": same, "same_outcome": agree,
            "succeeded_over_ros": succeeded, "different": different}


def _simulator(domain_id: int, options: list[str]) -> subprocess.Popen[bytes]:
    return subprocess.Popen(
        _python("import sys; from homebot.cli import main; sys.exit(main())", "sim", "serve",
                "--domain-id", str(domain_id), *options),
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _lost(trials: int = 3) -> dict[str, Any]:
    """``homebot sim serve --crash-after 6`` dies in the middle of the fetch (after the first
    navigation); the wall time from its death to ``run-task --robot ros`` ending the task."""
    from homebot.cli import main

    delays = []
    with tempfile.TemporaryDirectory() as folder:
        task = Path(folder) / "task.yaml"
        task.write_text(_TASK, encoding="utf-8")
        for trial in track(range(trials), "a lost robot"):
            domain_id = _DOMAIN - 25 - trial
            server = subprocess.Popen(
                _python("import sys; from homebot.cli import main; sys.exit(main())", "sim",
                        "serve", "--domain-id", str(domain_id), "--crash-after", "6"),
                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            with open(os.devnull, "w") as quiet:
                stdout, sys.stdout = sys.stdout, quiet
                try:
                    status = main(["run-task", str(task), "--robot", "ros", "--domain-id",
                                   str(domain_id)])
                finally:
                    sys.stdout = stdout
            ended = time.time()
            _, said = server.communicate(timeout=30)
            crashed = [float(word) for line in said.splitlines() if "on purpose at" in line
                       for word in line.split() if word.replace(".", "").isdigit()]
            if status == 1 and crashed:
                delays.append(ended - crashed[0])
    return {"trials": trials, "ended_with_robot_lost": len(delays),
            "worst_wall_seconds": round(max(delays), 3) if delays else None,
            "mean_wall_seconds": round(sum(delays) / len(delays), 3) if delays else None}


class _Truth:
    """The simulator's true pose at the body's last tick, from ``/homebot/truth``."""

    def __init__(self, truths: Any, body: Any) -> None:
        self.truths, self.body = truths, body
        self.poses: dict[float, tuple[float, float, float]] = {}

    def __call__(self) -> tuple[float, float, float]:
        from homebot.transport.messages import pose_of, seconds
        from homebot.transport.node import TransportError

        arrived = self.truths.take()
        for _ in range(100):  # the truth of this tick (bounded: 100 waits of 0.05 s)
            for message in arrived:
                pose = pose_of(message.pose)
                self.poses[round(seconds(message.header.stamp), 3)] = (pose.x, pose.y,
                                                                       pose.theta)
            found = self.poses.get(round(self.body.now(), 3))
            if found is not None:
                return found
            arrived = self.truths.wait(0.05)
        raise TransportError("no true pose from homebot sim serve --body")


def _tracking(runs: int, seconds: int) -> dict[str, Any]:
    """The localisation benchmark's tracking drive on ``SimBody`` here and on ``RosBody``
    over ``homebot sim serve --body`` (same seeds, three people walking), judged by the truth."""
    import numpy as np

    from homebot.navigation import Navigator
    from homebot.robot import DriveKind, VelocityLimits
    from homebot.transport.node import Node, loopback
    from homebot.transport.ros_body import RosBody
    from homebot.trials.localisation import (
        WALKERS,
        LocalisationSetting,
        tracking_drive,
        tracking_run,
    )
    from homebot.world import World

    world = World.load("apartment")
    navigator = Navigator(world)
    setting = LocalisationSetting(world, navigator.grid, navigator)
    robot = world.robot
    errors: dict[str, list[float]] = {"in_process": [], "over_ros": []}
    for seed in range(runs):
        errors["in_process"].extend(tracking_run(setting, seed, seconds, 0.0)[0])
        domain_id = _DOMAIN - 40 - seed % 20
        server = subprocess.Popen(
            _python("import sys; from homebot.cli import main; sys.exit(main())", "sim",
                    "serve", "--body", "--walkers", str(WALKERS), "--seed", str(seed),
                    "--domain-id", str(domain_id)),
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            node = Node(loopback(domain_id))
            truths = node.subscription("/homebot/truth", "geometry_msgs/msg/PoseStamped")
            body = RosBody(node, drive=DriveKind(robot.drive),
                           limits=VelocityLimits(robot.speed, robot.angular_speed),
                           radius=robot.radius, tick_period=0.05)
            body.connect(60.0)
            truth = _Truth(truths, body)
            errors["over_ros"].extend(tracking_drive(setting, body, truth, seed, seconds)[0])
        finally:
            server.kill()
            server.wait(10)

    def figures(values: list[float]) -> dict[str, Any]:
        return {"median_cm": round(100 * float(np.median(values)), 2),
                "p95_cm": round(100 * float(np.percentile(values, 95)), 2),
                "max_cm": round(100 * max(values), 2), "samples": len(values)}

    here, there = figures(errors["in_process"]), figures(errors["over_ros"])
    return {"runs": runs, "seconds": seconds, "in_process": here, "over_ros": there,
            "median_ratio": round(there["median_cm"] / here["median_cm"], 3)
            if here["median_cm"] else None}


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Run the chosen experiments; print a table unless ``console`` is None."""
    require_ros()
    figures: dict[str, Any] = {"benchmark": "transport"}
    if args.only in ("all", "throughput"):
        figures["laser_scan"] = {"rate": args.scan_rate,
                                 **_throughput("scan", args.scan_rate, args.seconds)}
        figures["point_cloud_320x240"] = {"rate": args.cloud_rate,
                                          **_throughput("cloud", args.cloud_rate, args.seconds)}
    if args.only in ("all", "fetch"):
        figures["fetch_over_ros"] = _fetch(args.seeds)
    if args.only in ("all", "lost"):
        figures["lost_robot"] = _lost()
    if args.only in ("all", "tracking"):
        figures["tracking_rosbody"] = _tracking(args.runs, args.drive_seconds)
    if console is not None:
        table = Table(title="ROS 2 transport (loopback, reliable QoS)")
        table.add_column("experiment")
        table.add_column("figures")
        for name, values in figures.items():
            if isinstance(values, dict):
                table.add_row(name, ", ".join(f"{key} {value}" for key, value in values.items()))
        console.print(table)
    return figures
