"""Errors a person can cause, all under one root.

Hierarchy::

    HomebotError                 anything a person typed or loaded is wrong
    ├── WorldError               a world file or world reference is invalid
    ├── TaskError                a task file or task step is invalid
    ├── NavigationError          no route exists (bad target, unreachable place)
    ├── MapError                 a map_server map (YAML + image) is malformed or does not fit
    ├── KnowledgeError           a knowledge-base file, query or update is invalid
    ├── GologError               a Golog program or action theory is malformed
    ├── PlanningError            an HTN domain, problem or planning goal is malformed
    ├── LanguageError            a command cannot be understood
    ├── DialogueError            a SitLog dialogue model is malformed or cannot go on
    ├── BenchmarkError           a benchmark's argument (a size, a seed, a file) is unusable
    ├── SpeechError              an audio file is unusable (empty, not WAV, too long) or the
    │                            speech extra is missing
    └── TransportError           ROS 2 cannot start (bad domain id or interface, the ros extra
        │                        missing) or the other side does not answer
        └── RobotLost            the robot's ROS 2 side stopped answering mid-task

Every message says what is wrong and how to fix it; the CLI prints it without a
traceback and exits with status 2. Expected failures while acting in the world
(an object not found, a door closed) are not errors: skills return them as
``Outcome`` values.
"""

from __future__ import annotations

__all__ = [
    "BenchmarkError",
    "DialogueError",
    "GologError",
    "HomebotError",
    "KnowledgeError",
    "LanguageError",
    "MapError",
    "NavigationError",
    "PlanningError",
    "RobotLost",
    "SpeechError",
    "TaskError",
    "TransportError",
    "WorldError",
]


class HomebotError(Exception):
    """Root of every error a person can cause by what they type or load."""


class WorldError(HomebotError):
    """A world file is malformed, or a name does not exist in the world."""


class TaskError(HomebotError):
    """A task file or step is malformed (unknown skill, missing argument)."""


class NavigationError(HomebotError):
    """A navigation target is unknown or has no pose."""


class MapError(HomebotError):
    """A ROS ``map_server`` map (YAML + PGM) is malformed, or does not cover its world."""


class KnowledgeError(HomebotError):
    """A knowledge-base file, query or update is invalid."""


class LanguageError(HomebotError):
    """A command cannot be parsed at all."""


class DialogueError(HomebotError):
    """A SitLog dialogue model is malformed (with its place), or its run cannot go on."""


class GologError(HomebotError):
    """A Golog program (text or Python) or its basic action theory is malformed."""


class PlanningError(HomebotError):
    """An HTN domain or problem (file or Python) or a planning goal is malformed."""


class BenchmarkError(HomebotError):
    """A benchmark's argument is unusable: a size of 0 or absurd, a bad seed, a missing file."""


class SpeechError(HomebotError):
    """Audio cannot be heard or spoken: an empty, non-WAV or overlong file, an unknown voice,
    or the speech extra is not installed."""


class TransportError(HomebotError):
    """The ROS 2 transport cannot start (a bad domain id, an interface that does not exist,
    the ros extra missing) or the other side does not answer in time."""


class RobotLost(TransportError):
    """The robot's ROS 2 side stopped answering (its process ended or the network went)."""
