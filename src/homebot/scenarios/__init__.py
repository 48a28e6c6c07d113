"""Wiring of the layers for runs in the simulated home: the one place they meet."""

from homebot.scenarios.runtime import SimulatedRun, disturbance_level, disturbed, probability

__all__ = ["SimulatedRun", "disturbance_level", "disturbed", "probability"]
