"""Errors a person can cause, all under one root.

Hierarchy::

    HomebotError                 anything a person typed or loaded is wrong
    ├── WorldError               a world file or world reference is invalid
    ├── TaskError                a task file or task step is invalid
    ├── NavigationError          no route exists (bad target, unreachable place)
    │   └── LocalPlannerError    a local controller asked wrongly (an empty path, a period
    │                            that is not positive)
    ├── MapError                 a map_server map (YAML + image) is malformed or does not fit
    ├── KnowledgeError           a knowledge-base file, query or update is invalid
    ├── GologError               a Golog program or action theory is malformed
    ├── PlanningError            an HTN domain, problem or planning goal is malformed
    ├── LanguageError            a command cannot be understood
    ├── DialogueError            a SitLog dialogue model is malformed or cannot go on
    ├── BenchmarkError           a benchmark's argument (a size, a seed, a file) is unusable
    ├── OptionError              a command-line option's value is unusable (a negative seed)
    ├── SpeechError              an audio file is unusable (empty, not WAV, too long) or the
    │                            speech extra is missing
    ├── BodyError                a robot body set up wrongly (a limit not positive, a part
    │   │                        out of range)
    │   └── PartMissing          the body has no such part: a camera, an arm, a microphone
    ├── FaceError                faces used wrongly (identifying before anyone is enrolled)
    ├── SceneError               an interaction scene cannot be loaded (unknown name, bad MJCF)
    ├── ConsoleError             the web console cannot do what the operator asked now
    └── TransportError           ROS 2 cannot start (bad domain id or interface, the ros extra
        │                        missing) or the other side does not answer
        ├── RobotLost            the robot's ROS 2 side stopped answering mid-task
        └── CallError            a Robot port call over ROS 2 names no method of the port or
                                 gives malformed arguments

Every message says what is wrong and how to fix it; the CLI prints it without a
traceback and exits with status 2; a message that lists problems lists the first
twenty and counts the rest (``homebot.text.problem_listing``). Expected failures while
acting in the world
(an object not found, a door closed) are not errors: skills return them as
``Outcome`` values.
"""

from __future__ import annotations

__all__ = [
    "BenchmarkError",
    "BodyError",
    "CallError",
    "ConsoleError",
    "DialogueError",
    "FaceError",
    "GologError",
    "HomebotError",
    "KnowledgeError",
    "LanguageError",
    "LocalPlannerError",
    "MapError",
    "NavigationError",
    "OptionError",
    "PartMissing",
    "PlanningError",
    "RobotLost",
    "SceneError",
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


class LocalPlannerError(NavigationError):
    """A local controller asked wrongly: an empty path, a radius or period that is not positive."""


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


class OptionError(HomebotError):
    """A command-line option's value is unusable (a negative ``--seed``)."""


class SpeechError(HomebotError):
    """Audio cannot be heard or spoken: an empty, non-WAV or overlong file, an unknown voice,
    or the speech extra is not installed."""


class BodyError(HomebotError):
    """A body set up wrongly: a limit that is not a positive number, a part out of range."""


class PartMissing(BodyError):
    """The body has no such part (yet): a camera, an arm, a microphone."""

    def __init__(self, part: str) -> None:
        super().__init__(f"this robot body has no {part}; it is fitted by a later module "
                         "or a robot that has one")


class FaceError(HomebotError):
    """Faces used wrongly: identifying before anyone is enrolled, an empty enrolment."""


class SceneError(HomebotError):
    """An interaction scene cannot be loaded (an unknown name, a malformed MJCF file)."""


class ConsoleError(HomebotError):
    """Something the operator asked that the console cannot do now (says why)."""


class TransportError(HomebotError):
    """The ROS 2 transport cannot start (a bad domain id, an interface that does not exist,
    the ros extra missing) or the other side does not answer in time."""


class RobotLost(TransportError):
    """The robot's ROS 2 side stopped answering (its process ended or the network went)."""


class CallError(TransportError):
    """A RobotCall names a method the port lacks or gives malformed arguments."""
