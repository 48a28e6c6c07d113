"""The simulated home behind the Robot port: ground truth, disturbances."""

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
    "InteractiveResponder",
    "PlanCache",
    "Responder",
    "ScriptedResponder",
    "SimRobot",
    "Simulation",
    "normalise_question",
]
