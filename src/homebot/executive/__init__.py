"""The executive: the one acting loop (retries, recovery, time budget) and the run report."""

from homebot.executive.executive import Executive, RunMark
from homebot.executive.recovery import PROTOCOLS, WAY_BLOCKED
from homebot.executive.report import RunDetail, RunReport, StepReport, print_report

__all__ = ["PROTOCOLS", "WAY_BLOCKED", "Executive", "RunDetail", "RunMark", "RunReport",
           "StepReport", "print_report"]
