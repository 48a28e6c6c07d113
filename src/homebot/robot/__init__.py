"""The Robot port that skills call; simulated and real robots implement it."""

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
    "Blocker",
    "Detection",
    "HelpRequest",
    "MoveReport",
    "PersonPercept",
    "Pose",
    "Robot",
]
