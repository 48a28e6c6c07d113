"""The ports: ``Robot`` (what skills call) and ``Body`` (what a robot's drivers offer)."""

from homebot.geometry import Pose
from homebot.robot.actions import Action, ActionStatus
from homebot.robot.body import (
    Arm,
    ArmState,
    Body,
    DriveKind,
    Gripper,
    GripperState,
    HeadState,
    JointTarget,
    LaserScan,
    Microphone,
    Odometry,
    Speaker,
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
    Robot,
)

__all__ = [
    "Action",
    "ActionStatus",
    "Arm",
    "ArmState",
    "Blocker",
    "Body",
    "CameraIntrinsics",
    "Detection",
    "DriveKind",
    "Gripper",
    "GripperState",
    "HeadState",
    "HelpRequest",
    "JointTarget",
    "LaserScan",
    "Microphone",
    "MoveReport",
    "Odometry",
    "PersonPercept",
    "Pose",
    "RgbdFrame",
    "Robot",
    "Speaker",
    "Twist",
    "VelocityLimits",
    "Wrench",
]
