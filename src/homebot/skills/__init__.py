"""Monitored skills: each executes, monitors its effect by sensing, and reports."""

from homebot.skills.catalogue import SKILLS, check_step, skill_named, spelled_as_world
from homebot.skills.places import OPERATOR
from homebot.skills.skill import ErrorCode, Outcome, Skill, SkillContext, Status, speak

__all__ = [
    "OPERATOR",
    "SKILLS",
    "ErrorCode",
    "Outcome",
    "Skill",
    "SkillContext",
    "Status",
    "check_step",
    "skill_named",
    "speak",
    "spelled_as_world",
]
