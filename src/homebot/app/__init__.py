"""The composition root: the one place the layers are wired into a run.

Every interface (the command line, the web console, the ROS 2 nodes, the benchmarks)
asks this package for what it runs, with typed settings and never with command-line
arguments: ``build_run(RunSettings(world=..., fidelity=Fidelity.EMBODIED))`` builds a
simulated home with the robot in either fidelity, its perception, beliefs and executive;
``conversation_for(run)`` the conversation one person holds with it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from homebot.lazy import lazy_exports

if TYPE_CHECKING:
    from homebot.app.conversation import QUESTION_COST, believed, conversation_for, told
    from homebot.app.fidelity import Fidelity, require_embodied
    from homebot.app.run import Run, RunSettings, build_run, disturbed

__all__ = [
    "QUESTION_COST",
    "Fidelity",
    "Run",
    "RunSettings",
    "believed",
    "build_run",
    "conversation_for",
    "disturbed",
    "require_embodied",
    "told",
]

__getattr__ = lazy_exports(globals())
