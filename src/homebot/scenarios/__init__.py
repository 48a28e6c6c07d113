"""Wiring of the layers for runs in the simulated home: the one place they meet."""

from homebot.scenarios.runtime import SimulatedRun, disturbed

__all__ = ["SimulatedRun", "disturbed"]
