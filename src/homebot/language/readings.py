"""Choosing among readings of a command by decision theory, with the cost of a question explicit.

CAESAR (§3.3) casts interpretation as decision-theoretic planning over interpretatory
actions: when an utterance has several readings, the robot weighs them by what it
believes and what its action theory allows, and asks only when asking is worth more.

Here a reading is the command with the ambiguous words replaced by one option ("the
table" -> "the kitchen table"). A reading the action theory does not allow (its parse is
not ok: "fetch the kitchen") has probability 0. The others are weighted by the robot's
beliefs: each search for an object at a place is as likely as the belief that it is there
(``found`` if believed there; otherwise the rest, ``1 - found``, spread evenly over the
home's other placements). With probability ``p`` of the best
reading, acting on it is worth ``p * success - (1 - p) * wrong``; asking first is worth
``success - question`` (the answer makes the reading certain). The robot guesses when
guessing is worth at least as much, and says which reading it took.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from homebot.language.result import ParseResult, ParseStatus
from homebot.task import Step

__all__ = ["ReadingModel", "choose_reading"]


@dataclass(frozen=True)
class ReadingModel:
    """What the robot believes (object -> placement) and what outcomes are worth.

    ``question`` is the explicit cost of asking back, on the scale where carrying out
    the meant command is worth ``success`` and carrying out a wrong one costs ``wrong``.
    """

    object_at: Mapping[str, str] = field(default_factory=dict)
    categories: Mapping[str, str] = field(default_factory=dict)  # object -> category
    question: float = 0.25
    success: float = 1.0
    wrong: float = 1.0
    found: float = 0.95  # the belief that an object is where the robot thinks it is
    places: int = 2  # how many placements the home has: the rest of the belief spreads over them

    def value_of_guess(self, probability: float) -> float:
        return probability * self.success - (1.0 - probability) * self.wrong

    def value_of_asking(self) -> float:
        return self.success - self.question

    def likelihood(self, steps: list[Step]) -> float:
        """How well a reading's steps fit the beliefs: the product over its searches."""
        weight = 1.0
        for step in steps:
            if step.skill != "find_object" or "placement" not in step.args:
                continue
            wanted, place = str(step.args["object"]), str(step.args["placement"])
            there = [name for name, at in self.object_at.items() if at == place and (
                name == wanted or self.categories.get(name) == wanted)]
            weight *= self.found if there else (1.0 - self.found) / max(1, self.places - 1)
        return weight


def choose_reading(result: ParseResult, model: ReadingModel,
                   parse: Callable[[str], ParseResult]) -> ParseResult:
    """The question ``result`` asks, or the reading worth more than asking it."""
    if result.status is not ParseStatus.CLARIFY or not result.options or not result.about:
        return result
    pattern = re.compile(r"\b" + re.escape(result.about) + r"\b", re.IGNORECASE)
    if not pattern.search(result.text):
        return result
    readings: list[tuple[str, ParseResult, float]] = []
    for option in result.options:
        parsed = parse(pattern.sub(option, result.text, count=1))
        weight = model.likelihood(parsed.steps) if parsed else 0.0  # the action theory
        readings.append((option, parsed, weight))
    total = sum(weight for _, _, weight in readings)
    if total <= 0.0:
        return result
    option, best, weight = max(readings, key=lambda reading: reading[2])
    probability = weight / total
    guess, ask = model.value_of_guess(probability), model.value_of_asking()
    if guess < ask:
        return result
    why = (f"I took '{result.about}' to mean the {option} (p = {probability:.2f}: guessing is "
           f"worth {guess:.2f}, asking {ask:.2f} with a question costing {model.question})")
    return ParseResult(ParseStatus.OK, result.text, steps=list(best.steps), assumed=why)
