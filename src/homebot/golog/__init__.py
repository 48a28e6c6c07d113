"""Golog / READYLOG: robot programs with decision-theoretic planning and execution monitoring.

A basic action theory (``Theory``) over fluents and primitive, stochastic,
sensing and exogenous actions; programs built in Python (``homebot.golog.build``)
or read from text (``parse_program``, ``parse_procedures``); ``solve`` plans
DTGolog policies with READYLOG's markers; the ``Interpreter`` runs programs
online through an ``Executor`` (the skills of the home, or a pure simulation).
"""

from homebot.golog.interpreter import Executor, Interpreter, Report, Run, SimulatedExecutor
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
    "Report",
    "Result",
    "Run",
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
