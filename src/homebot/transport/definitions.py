"""Interface definitions the rosbags typestore lacks, as their packages write them.

``nav2_msgs/action/NavigateToPose`` is Nav2's (Humble) and ``action_msgs/srv/CancelGoal``
rcl_interfaces' (Humble), copied field for field. ``homebot_msgs`` are homebot's own
interfaces: a generic robot call (the Robot port's methods other than navigation, with
JSON arguments and results, for ``homebot sim serve`` and robots that offer it), the
command action and the parse service of ``homebot ros serve``.
"""

from __future__ import annotations

__all__ = ["ACTIONS", "MESSAGES", "SERVICES"]

#: Messages by full name (none yet beyond the typestore's).
MESSAGES: dict[str, str] = {}

#: Services: request ``---`` response.
SERVICES: dict[str, str] = {
    "action_msgs/srv/CancelGoal": """\
action_msgs/GoalInfo goal_info
---
int8 ERROR_NONE=0
int8 ERROR_REJECTED=1
int8 ERROR_UNKNOWN_GOAL_ID=2
int8 ERROR_GOAL_TERMINATED=3
int8 return_code
action_msgs/GoalInfo[] goals_canceling""",
    "homebot_msgs/srv/RobotCall": """\
string method
string arguments
---
string result
float64 now
string events""",
    "homebot_msgs/srv/Parse": """\
string command
---
bool understood
string steps
string error""",
}

#: Actions: goal ``---`` result ``---`` feedback.
ACTIONS: dict[str, str] = {
    "nav2_msgs/action/NavigateToPose": """\
geometry_msgs/PoseStamped pose
string behavior_tree
---
std_msgs/Empty result
---
geometry_msgs/PoseStamped current_pose
builtin_interfaces/Duration navigation_time
builtin_interfaces/Duration estimated_time_remaining
int16 number_of_recoveries
float32 distance_remaining""",
    "homebot_msgs/action/Command": """\
string command
---
bool success
string speech
string reason
---
string step""",
}
