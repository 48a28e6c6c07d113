"""HTN planning (SHOP2/JSHOP2 style) with monitored plan execution (Care-O-bot "Jenny")."""

from homebot.htn.acting import OPERATOR_SKILLS, HtnTrace, OperatorReport, PlanActor, step_for
from homebot.htn.domain import Branch, Domain, Method, Operator, Problem
from homebot.htn.home import (
    HOME_TASKS,
    ROBOT,
    Goal,
    Names,
    goals_from_steps,
    home_domain,
    home_domain_path,
    load_domain,
    load_functions,
    state_from_beliefs,
    symbol,
)
from homebot.htn.jshop import read_domain, read_domain_text, read_problem_text, read_problems
from homebot.htn.logic import Axiom, expression
from homebot.htn.planner import (
    DecompositionNode,
    Plan,
    Planner,
    PlanningResult,
    PlanStep,
    find_cheapest_plan,
    find_plan,
    find_plans,
)
from homebot.htn.render import plan_dot, plans_json, task_network_text
from homebot.htn.state import State

__all__ = [
    "HOME_TASKS",
    "OPERATOR_SKILLS",
    "ROBOT",
    "Axiom",
    "Branch",
    "DecompositionNode",
    "Domain",
    "Goal",
    "HtnTrace",
    "Method",
    "Names",
    "Operator",
    "OperatorReport",
    "Plan",
    "PlanActor",
    "PlanStep",
    "Planner",
    "PlanningResult",
    "Problem",
    "State",
    "expression",
    "find_cheapest_plan",
    "find_plan",
    "find_plans",
    "goals_from_steps",
    "home_domain",
    "home_domain_path",
    "load_domain",
    "load_functions",
    "plan_dot",
    "plans_json",
    "read_domain",
    "read_domain_text",
    "read_problem_text",
    "read_problems",
    "state_from_beliefs",
    "step_for",
    "symbol",
    "task_network_text",
]
