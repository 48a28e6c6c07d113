"""The web console: watch the simulated home live and command the robot on three levels."""

from __future__ import annotations

from homebot.web.console import Console, ConsoleSettings, static_map

__all__ = ["Console", "ConsoleSettings", "static_map"]
