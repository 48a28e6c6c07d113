"""The ports: ``Robot`` (what skills call) and ``Body`` (what a robot's drivers offer)."""

from homebot.robot.actions import Action, ActionStatus
from homebot.robot.body import (
    Body,
    BodyError,
    DriveKind,
    HeadState,
    LaserScan,
    Odometry,
    PartMissing,
    Twist,
    VelocityLimits,
)
from homebot.robot.port import (
    Blocker,
    Detection,
    HelpRequest,
    MoveReport,
    PersonPercept,
    Pose,
    Robot,
)

__all__ = [
    "Action",
    "ActionStatus",
    "Blocker",
    "Body",
    "BodyError",
    "Detection",
    "DriveKind",
    "HeadState",
    "HelpRequest",
    "LaserScan",
    "MoveReport",
    "Odometry",
    "PartMissing",
    "PersonPercept",
    "Pose",
    "Robot",
    "Twist",
    "VelocityLimits",
]
