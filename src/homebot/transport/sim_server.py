"""A simulated robot on ROS 2: what ``homebot sim serve`` runs.

It offers what a real robot running Nav2 offers: the ``/map`` (transient local, as
``map_server`` latches it), ``/odom`` and ``/tf`` (map -> odom -> base_link), and a
``nav2_msgs/action/NavigateToPose`` server at ``/navigate_to_pose``. The Robot port's other
methods go over ``homebot_msgs/srv/RobotCall`` at ``/homebot/robot``, whose reply carries
the simulated time and the simulator's events since the last reply (so a remote executive
keeps the same event log as an in-process one). ``move_options`` sets the doors to avoid
and the person to escort for the next goal; ``last_move`` returns the last goal's report;
``final_state`` logs where the run left things (the simulator's truth, as an in-process
run logs it).

Every call is checked against its method's schema (``homebot.transport.calls``) before it
reaches the robot; a call that fails (a bad method, malformed arguments, or an error in the
robot) is answered with ``{"error": reason}`` as its result and logged, and the server goes
on. A navigation goal whose pose is not finite, outside the map, or not in the map frame
ends ABORTED.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from homebot.errors import CallError
from homebot.events import EventLog
from homebot.geometry import Pose
from homebot.robot import MoveReport, Robot
from homebot.transport.actions import ActionServer, GoalContext, GoalStatus
from homebot.transport.calls import MoveOptions, NoArguments, encode, parse_arguments, serve
from homebot.transport.messages import pose_stamped, stamp, yaw_of
from homebot.transport.naming import MAP_QOS
from homebot.transport.node import Arrivals, Node, shown
from homebot.world import OccupancyGrid, World

__all__ = ["NAVIGATE_ACTION", "ROBOT_CALL", "SimServer"]

NAVIGATE_ACTION = "/navigate_to_pose"
ROBOT_CALL = "/homebot/robot"
NAVIGATE_TO_POSE = "nav2_msgs/action/NavigateToPose"


class SimServer:
    """Serves one simulated robot (any ``Robot``) and its simulator's event log."""

    def __init__(self, node: Node, robot: Robot, world: World, events: EventLog,
                 final_state: Callable[[], None] | None = None) -> None:
        self.node, self.robot, self.world, self.events = node, robot, world, events
        self.final_state = final_state
        self.calls = node.service(ROBOT_CALL, "homebot_msgs/srv/RobotCall", self._call,
                                  self._refuse)
        self.navigate = ActionServer(node, NAVIGATE_ACTION, NAVIGATE_TO_POSE, self._navigate,
                                     clock=robot.now)
        self._arrivals = Arrivals(node, [self.calls.requests,
                                         *self.navigate.request_subscriptions()])
        self.map = node.publisher("/map", "nav_msgs/msg/OccupancyGrid", MAP_QOS)
        self.odom = node.publisher("/odom", "nav_msgs/msg/Odometry")
        self.tf = node.publisher("/tf", "tf2_msgs/msg/TFMessage")
        self._shipped = 0  # events already sent to the client
        self._avoid: frozenset[str] = frozenset()
        self._escort: str | None = None
        self._last_move: MoveReport | None = None
        self.calls_served = 0  #: robot calls answered so far
        grid = OccupancyGrid.from_world(world)
        (x0, y0), (rows, cols) = grid.origin, grid.shape
        #: where a goal may lie: the map's extent (x from, x to, y from, y to)
        self.bounds = (x0, x0 + cols * grid.resolution, y0, y0 + rows * grid.resolution)
        self.map.publish(self._map_message(grid))
        self.publish_state()

    def spin_once(self, timeout: float = 0.1) -> int:
        """Answer what arrived (waiting up to ``timeout`` s for a request); how many."""
        self._arrivals.wait(timeout)
        return self.navigate.poll() + self.calls.poll() + self.navigate.poll()

    # ------------------------------------------------------------ the calls

    def _call(self, request: Any) -> dict[str, Any]:
        self.calls_served += 1
        result = self._run(str(request.method), str(request.arguments))
        self.publish_state()
        return {"result": result, "now": self.robot.now(), "events": self._new_events()}

    def _run(self, method: str, arguments: str) -> str:
        if method == "move_options":
            options = parse_arguments(method, arguments, MoveOptions)
            self._avoid, self._escort = frozenset(options.avoid_doors), options.escort
            return "null"
        if method in ("final_state", "last_move"):
            parse_arguments(method, arguments, NoArguments)
            if method == "last_move":
                return json.dumps(encode(self._last_move))
            if self.final_state is None:
                raise CallError("RobotCall final_state: this server keeps no final state")
            self.final_state()
            return "null"
        return serve(self.robot, method, arguments)

    def _refuse(self, reason: str) -> dict[str, Any]:
        """The reply to a call that failed: the reason as its result's ``error``."""
        return {"result": json.dumps({"error": reason}), "now": self.robot.now(),
                "events": self._new_events()}

    def _new_events(self) -> str:
        events = self.events.since(self._shipped)
        self._shipped = self.events.count
        return json.dumps([[event.time, event.kind, event.data] for event in events],
                          ensure_ascii=False)

    def _navigate(self, goal: Any, context: GoalContext) -> tuple[GoalStatus, dict[str, Any]]:
        pose = goal.pose.pose
        frame = str(goal.pose.header.frame_id)
        if frame not in ("map", ""):
            raise CallError(f"{NAVIGATE_ACTION}: a goal in frame {shown(frame)}; this robot "
                            "takes goals in 'map'")
        target = Pose(pose.position.x, pose.position.y, yaw_of(pose.orientation))
        if not all(math.isfinite(value) for value in (target.x, target.y, target.theta)):
            raise CallError(f"{NAVIGATE_ACTION}: a goal pose that is not finite ({target})")
        x_from, x_to, y_from, y_to = self.bounds
        if not (x_from <= target.x <= x_to and y_from <= target.y <= y_to):
            raise CallError(f"{NAVIGATE_ACTION}: the goal ({target.x:g}, {target.y:g}) is "
                            f"outside the map (x {x_from:g} to {x_to:g}, y {y_from:g} to "
                            f"{y_to:g})")
        report = self.robot.move_to(target, self._avoid, self._escort)
        self._avoid, self._escort, self._last_move = frozenset(), None, report
        self.publish_state()
        context.publish_feedback(current_pose=pose_stamped(self.node.types, report.pose,
                                                           self.robot.now()),
                                 distance_remaining=math.dist(report.pose.xy(), target.xy()))
        return (GoalStatus.SUCCEEDED if report.reached else GoalStatus.ABORTED), {}

    # ------------------------------------------------------------ state topics

    def publish_state(self) -> None:
        """``/odom`` and ``/tf`` at the robot's pose (odom coincides with map here)."""
        types, now = self.node.types, self.robot.now()
        pose = self.robot.pose()
        odometry = types.new("nav_msgs/msg/Odometry",
                             header=types.new("std_msgs/msg/Header", stamp=stamp(types, now),
                                              frame_id="odom"),
                             child_frame_id="base_link")
        odometry.pose.pose = pose_stamped(types, pose, now).pose
        self.odom.publish(odometry)
        transforms = []
        for parent, child, at in (("map", "odom", Pose(0.0, 0.0, 0.0)),
                                  ("odom", "base_link", pose)):
            transform = types.new("geometry_msgs/msg/TransformStamped",
                                  header=types.new("std_msgs/msg/Header",
                                                   stamp=stamp(types, now), frame_id=parent),
                                  child_frame_id=child)
            placed = pose_stamped(types, at, now).pose
            transform.transform.translation.x = placed.position.x
            transform.transform.translation.y = placed.position.y
            transform.transform.rotation = placed.orientation
            transforms.append(transform)
        self.tf.publish(types.new("tf2_msgs/msg/TFMessage", transforms=transforms))

    def _map_message(self, grid: OccupancyGrid) -> Any:
        types = self.node.types
        rows, cols = grid.shape
        data = np.where(np.asarray(grid.occupied).reshape(rows, cols), 100, 0).astype(np.int8)
        info = types.new("nav_msgs/msg/MapMetaData", resolution=grid.resolution,
                         width=cols, height=rows)
        info.origin.position.x, info.origin.position.y = grid.origin
        info.origin.orientation.w = 1.0
        return types.new("nav_msgs/msg/OccupancyGrid",
                         header=types.new("std_msgs/msg/Header", frame_id="map"),
                         info=info, data=data.ravel().tolist())
