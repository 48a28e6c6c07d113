"""The simulated home behind the Robot port: ground truth, clock, disturbances."""

from homebot.sim.clock import Clock
from homebot.sim.people import (
    InteractiveResponder,
    Responder,
    ScriptedResponder,
    normalise_question,
)
from homebot.sim.robot import ActionDurations, SimRobot
from homebot.sim.simulation import HAND_PREFIX, PERSON_PREFIX, PlanCache, Simulation

__all__ = [
    "HAND_PREFIX",
    "PERSON_PREFIX",
    "ActionDurations",
    "Clock",
    "InteractiveResponder",
    "PlanCache",
    "Responder",
    "ScriptedResponder",
    "SimRobot",
    "Simulation",
    "normalise_question",
]
