"""Trials: the episodes that scenarios and benchmarks run, and the referees that judge them.

An episode generator draws seeded tasks or scenes (fetch-and-deliver tasks, GPSR commands
the home can satisfy, table-top scenes, physical interactions with a person); a referee
judges what happened against the simulator's ground truth, never against the robot's own
report. Referees are the only code besides the simulator (and ``homebot.app``, which builds
it) that reads the truth. Product scenarios (``homebot.scenarios.library``) and the
benchmarks (``homebot.bench``, which time, loop and print figures) both use them.

Each module is imported on its own (several need the ``embodied`` extra), so this package
exposes nothing itself.
"""

from __future__ import annotations

__all__: list[str] = []
