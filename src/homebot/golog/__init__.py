"""Golog / READYLOG: robot programs with decision-theoretic planning and execution monitoring.

A basic action theory (``Theory``: fluents; primitive, stochastic, sensing and
exogenous actions; progression) in ``theory``; program constructs in
``program`` (with IndiGolog's ``search``); formulas in ``expressions``; the
Python embedding in ``build``; the textual syntax in ``syntax``; static checks
in ``checking``; ``solve`` as DTGolog's forward search with READYLOG's markers
in ``planner`` and ``policy``; Trans/Final in ``semantics``; the online
``Interpreter`` with its executors in ``interpreter`` (a pure simulation) and
``skill_executor`` (the home's skills); shipped domains in ``domains``.
"""

from homebot.golog.interpreter import (
    Executor,
    Interpreter,
    ProgramTrace,
    Report,
    SimulatedExecutor,
)
from homebot.golog.planner import Planner, plan, project
from homebot.golog.policy import Policy, Result, policy_actions, policy_text
from homebot.golog.program import Procedure, Program
from homebot.golog.skill_executor import SkillExecutor
from homebot.golog.syntax import parse_procedures, parse_program
from homebot.golog.theory import ActionSchema, Fluent, GroundAction, Situation, State, Theory

__all__ = [
    "ActionSchema",
    "Executor",
    "Fluent",
    "GroundAction",
    "Interpreter",
    "Planner",
    "Policy",
    "Procedure",
    "Program",
    "ProgramTrace",
    "Report",
    "Result",
    "SimulatedExecutor",
    "Situation",
    "SkillExecutor",
    "State",
    "Theory",
    "parse_procedures",
    "parse_program",
    "plan",
    "policy_actions",
    "policy_text",
    "project",
]
