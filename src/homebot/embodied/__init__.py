"""The embodied robot: the Robot port over a Body, through localisation and navigation."""

from homebot.embodied.conversation import Conversation
from homebot.embodied.looking import TableLook
from homebot.embodied.people_look import PeopleLook
from homebot.embodied.robot import BodyRobot

__all__ = ["BodyRobot", "Conversation", "PeopleLook", "TableLook"]
