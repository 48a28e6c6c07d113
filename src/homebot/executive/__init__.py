"""The executive: runs tasks with retries and recovery protocols, and reports."""

from homebot.executive.executive import Executive
from homebot.executive.recovery import PROTOCOLS, WAY_BLOCKED
from homebot.executive.report import StepReport, TaskReport

__all__ = ["PROTOCOLS", "WAY_BLOCKED", "Executive", "StepReport", "TaskReport"]
