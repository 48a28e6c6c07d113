"""What a scenario takes from its caller: the shared options it declares, and a run builder.

Scenarios sit at the trials rank, below the composition root (``homebot.app``) and the
command line, so they neither build runs nor parse options themselves. A scenario module
lists the shared options it takes in ``SHARED_OPTIONS``; the command line declares them
with its own argparse helpers and hands ``run`` typed values and a ``RunBuilder`` that
builds a run (``homebot.app.Run`` is one) in the fidelity asked for.
"""

from __future__ import annotations

import typing
from dataclasses import dataclass
from enum import Enum

from homebot.events import EventLog
from homebot.executive import Executive, RunReport
from homebot.executive.recovery import Protocol
from homebot.navigation import Navigator
from homebot.robot import Robot
from homebot.sim import Responder, Simulation
from homebot.skills import SkillContext
from homebot.task import Task
from homebot.world import DisturbanceModel, World

__all__ = ["OptionKind", "RunBuilder", "ScenarioRun", "SharedOption"]


class OptionKind(Enum):
    """The kinds of shared option the command line knows how to declare and check."""

    FIDELITY = "fidelity"  #: ``--fidelity symbolic|embodied``; it goes into the builder
    DISTURBANCE_LEVEL = "disturbance level"  #: 0 (none) to 6
    PROBABILITY = "probability"  #: 0 to 1


@dataclass(frozen=True)
class SharedOption:
    """One option a scenario takes whose checking belongs to the command line."""

    kind: OptionKind
    flag: str = ""  #: e.g. ``--level``; unused for the fidelity
    default: float = 0.0
    help: str = ""


class ScenarioRun(typing.Protocol):
    """What a scenario uses of a run (``homebot.app.Run`` is one)."""

    @property
    def world(self) -> World: ...

    @property
    def simulation(self) -> Simulation: ...

    @property
    def robot(self) -> Robot: ...

    @property
    def context(self) -> SkillContext: ...

    @property
    def executive(self) -> Executive: ...

    @property
    def events(self) -> EventLog: ...

    def run(self, task: Task) -> RunReport[None]: ...

    def record_final_state(self) -> None:
        """Log where the run left things, for the map of the last run."""


class RunBuilder(typing.Protocol):
    """Builds a fresh run in the fidelity the caller chose.

    ``level`` asks for the caller's disturbances at that level (0 to 6, None: none);
    ``disturbances`` gives a model outright.
    """

    def __call__(self, world: World, *, seed: int, level: float | None = None,
                 disturbances: DisturbanceModel | None = None,
                 responder: Responder | None = None, inference: Protocol | None = None,
                 navigator: Navigator | None = None) -> ScenarioRun: ...
