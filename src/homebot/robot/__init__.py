"""The ports: ``Robot`` (what skills call) and ``Body`` (what a robot's drivers offer)."""

from homebot.robot.actions import Action, ActionStatus
from homebot.robot.body import (
    Arm,
    ArmState,
    Body,
    BodyError,
    DriveKind,
    Gripper,
    GripperState,
    HeadState,
    JointTarget,
    LaserScan,
    Odometry,
    PartMissing,
    Twist,
    VelocityLimits,
    Wrench,
)
from homebot.robot.camera import CameraIntrinsics, RgbdFrame
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
    "Arm",
    "ArmState",
    "Blocker",
    "Body",
    "BodyError",
    "CameraIntrinsics",
    "Detection",
    "DriveKind",
    "Gripper",
    "GripperState",
    "HeadState",
    "HelpRequest",
    "JointTarget",
    "LaserScan",
    "MoveReport",
    "Odometry",
    "PartMissing",
    "PersonPercept",
    "Pose",
    "RgbdFrame",
    "Robot",
    "Twist",
    "VelocityLimits",
    "Wrench",
]
