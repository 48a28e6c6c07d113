"""A small kinematic ``Body`` for navigation tests: round obstacles, a ray-cast laser, no noise."""

from __future__ import annotations

import math

import numpy as np

from homebot.geometry import Pose
from homebot.robot import Body, DriveKind, HeadState, LaserScan, Odometry, Twist, VelocityLimits


class FakeBody(Body):
    """A base among round obstacles ``(x, y, radius)``; it records every touch as a collision."""

    def __init__(self, pose: Pose, obstacles: list[tuple[float, float, float]] | None = None,
                 drive: DriveKind = DriveKind.DIFFERENTIAL) -> None:
        self.drive = drive
        self.limits = VelocityLimits(0.5, 1.2, 1.0, 2.5)
        self.radius = 0.25
        self.tick_period = 0.05
        self.pose = pose
        self.obstacles = np.asarray(obstacles or [], dtype=float).reshape(-1, 3)
        self.velocity = Twist()
        self.command = Twist()
        self.commands: list[Twist] = []
        self.collisions = 0
        self.clock = 0.0
        self.min_clearance = math.inf

    def now(self) -> float:
        return self.clock

    def command_velocity(self, twist: Twist) -> None:
        self.command = self.limits.clip(twist, self.drive)
        self.commands.append(self.command)

    def tick(self, ticks: int = 1) -> None:
        for _ in range(ticks):
            dt, limits, now = self.tick_period, self.limits, self.velocity
            a, w = limits.linear_acceleration * dt, limits.angular_acceleration * dt
            self.velocity = Twist(now.vx + max(-a, min(a, self.command.vx - now.vx)),
                                  now.vy + max(-a, min(a, self.command.vy - now.vy)),
                                  now.wz + max(-w, min(w, self.command.wz - now.wz)))
            v, pose = self.velocity, self.pose
            middle = pose.theta + v.wz * dt / 2
            x = pose.x + (v.vx * math.cos(middle) - v.vy * math.sin(middle)) * dt
            y = pose.y + (v.vx * math.sin(middle) + v.vy * math.cos(middle)) * dt
            clearance = self._clearance(x, y)
            if clearance < self.radius:
                self.collisions += 1
                self.velocity = Twist()
            else:
                self.pose = Pose(x, y, pose.theta + v.wz * dt)
                self.min_clearance = min(self.min_clearance, clearance)
            self.clock += dt

    def _clearance(self, x: float, y: float) -> float:
        if not len(self.obstacles):
            return math.inf
        gaps = np.hypot(self.obstacles[:, 0] - x, self.obstacles[:, 1] - y) - self.obstacles[:, 2]
        return float(gaps.min())

    def odometry(self) -> Odometry:
        return Odometry(self.clock, self.pose, self.velocity)

    def scan(self) -> LaserScan:
        beams = 181
        angles = np.linspace(-3 * math.pi / 4, 3 * math.pi / 4, beams)
        ranges = np.full(beams, np.inf)
        world = angles + self.pose.theta
        dx, dy = np.cos(world), np.sin(world)
        for ox, oy, radius in self.obstacles:
            fx, fy = self.pose.x - ox, self.pose.y - oy
            b = fx * dx + fy * dy
            c = fx * fx + fy * fy - radius * radius
            disc = b * b - c
            hit = disc >= 0
            t = -b - np.sqrt(np.where(hit, disc, 0.0))
            ranges = np.where(hit & (t > 0) & (t < ranges), t, ranges)
        ranges = np.where(ranges <= 8.0, ranges, np.inf)
        return LaserScan(self.clock, -3 * math.pi / 4, float(angles[1] - angles[0]), 0.05, 8.0,
                         ranges)

    def head(self) -> HeadState:
        return HeadState()

    def point_head(self, pan: float, tilt: float) -> None:
        pass

    def emergency_stop(self, engaged: bool = True) -> None:
        pass

    @property
    def stopped(self) -> bool:
        return False


def wall(x0: float, y0: float, x1: float, y1: float, spacing: float = 0.08,
         radius: float = 0.05) -> list[tuple[float, float, float]]:
    """A wall as a row of small round posts (the laser and the bumper see it alike)."""
    count = max(int(math.dist((x0, y0), (x1, y1)) / spacing), 1)
    return [(x0 + (x1 - x0) * i / count, y0 + (y1 - y0) * i / count, radius)
            for i in range(count + 1)]
