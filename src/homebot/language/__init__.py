"""Understanding commands: GPSR sentences to skill steps, questions or refusals."""

from homebot.language.context import Discourse
from homebot.language.parser import parse_command
from homebot.language.readings import ReadingModel
from homebot.language.result import ParseResult, ParseStatus
from homebot.language.vocabulary import Entity, Vocabulary

__all__ = ["Discourse", "Entity", "ParseResult", "ParseStatus", "ReadingModel", "Vocabulary",
           "parse_command"]
