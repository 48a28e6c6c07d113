"""The daily-life inference cycle (Golem-III §7-§8): diagnosis, decision and planning on demand."""

from homebot.inference.cycle import CycleRecord, InferenceCycle
from homebot.inference.decision import Decision, Rewards, decide
from homebot.inference.diagnosis import AssistantAction, Diagnosis, diagnose
from homebot.inference.inventory import CUSTOMER, ROBOT, Inventory, KbChange
from homebot.inference.observation import (
    Observation,
    PutBack,
    fulfil_cognitive_obligations,
    observe,
)
from homebot.inference.planning import (
    HAND,
    USER,
    ActionModel,
    BasicAction,
    Carry,
    Plan,
    plan_carries,
)
from homebot.inference.service import age_in_words, fetch_task, requested_product

__all__ = [
    "CUSTOMER",
    "HAND",
    "ROBOT",
    "USER",
    "ActionModel",
    "AssistantAction",
    "BasicAction",
    "Carry",
    "CycleRecord",
    "Decision",
    "Diagnosis",
    "InferenceCycle",
    "Inventory",
    "KbChange",
    "Observation",
    "Plan",
    "PutBack",
    "Rewards",
    "age_in_words",
    "decide",
    "diagnose",
    "fetch_task",
    "fulfil_cognitive_obligations",
    "observe",
    "plan_carries",
    "requested_product",
]
