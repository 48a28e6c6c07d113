"""The summary every scenario returns and ``homebot scenario --json`` prints."""

from __future__ import annotations

from typing import Any

from homebot.executive import RunReport

__all__ = ["report_actions", "scenario_summary"]


def scenario_summary(name: str, success: bool, actions: list[Any], speech: list[str],
                     **figures: Any) -> dict[str, Any]:
    """``{"scenario", "success", "actions", "speech"}`` plus scenario-specific figures."""
    return {"scenario": name, "success": success, "actions": actions, "speech": speech,
            **figures}


def report_actions(report: RunReport[Any]) -> list[dict[str, Any]]:
    """The steps of a task report as summary actions: skill, args, status, error."""
    return [step.to_dict() for step in report.steps]
