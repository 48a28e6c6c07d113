"""``Conversation``: one person talking to the robot in one home, turn after turn.

Each turn is a command, an answer to the robot's question, or "stop". What persists
between turns (the seed's dialogue, Cosero §7.2.2; CAESAR §3.3's clarification):

- a question the robot asked ("Which table do you mean?") is answered in the next turn,
  and the command goes on with the answer in it;
- "it", "them" and "that" refer back to what an earlier command handled;
- what a person answered to ``ask`` is relayed to the operator ("Lisa would like a beer");
- "stop" or "cancel" heard while a task runs ends it between two steps; said while a
  question is open, it drops the command.

The conversation runs tasks through ``run`` (a ``Run.run`` or any callable with
its signature) and never reads the simulator: what it knows of the world is the reports.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from homebot.errors import LanguageError
from homebot.executive.report import RunReport
from homebot.language import (
    Discourse,
    ParseResult,
    ParseStatus,
    ReadingModel,
    Vocabulary,
    parse_command,
)
from homebot.language.lexicon import QUANTITIES
from homebot.task import Step, Task

__all__ = ["STOP_WORDS", "Conversation", "Turn", "relay_sentence"]

Runner = Callable[..., RunReport[Any]]
STOP_WORDS = frozenset({"stop", "cancel", "stop it", "stop that", "cancel that",
                        "never mind", "nevermind", "forget it", "abort", "halt", "wait stop"})
_YES = frozenset({"yes", "yes please", "yeah", "sure", "ok", "okay", "go ahead", "do it"})
_QUANTITY_WORDS = sorted((phrase for phrase, _ in QUANTITIES), key=len, reverse=True)
_QUANTITY_RE = re.compile(r"\b(" + "|".join(re.escape(q) for q in _QUANTITY_WORDS) + r")\b",
                          re.IGNORECASE)
_THAT_RE = re.compile(r"\bthat( one)?\s*([.!?]?)\s*$", re.IGNORECASE)


@dataclass
class Turn:
    """What happened in one turn: what was heard, what the robot made of it and said."""

    heard: str
    status: str  #: done, failed, asked, refused, stopped, cancelled or relayed
    said: list[str] = field(default_factory=list)
    parse: ParseResult | None = None
    report: RunReport[Any] | None = None

    @property
    def question(self) -> str | None:
        return self.parse.question if self.parse is not None else None


def _normalised(text: str) -> str:
    return " ".join(re.sub(r"[^\w' ]+", " ", text.lower()).split())


def relay_sentence(person: str, question: str, answer: str) -> str:
    """How the robot passes on an answer: "Lisa would like a beer", "João is from Porto"."""
    asked = _normalised(question)
    answer = answer.strip().rstrip(".")
    if asked.startswith("what would you like"):
        return f"{person} would like {answer}."
    if asked == "where are you from":
        return f"{person} is from {answer}."
    match = re.fullmatch(r"what is your (.+)", asked)
    if match is not None:
        return f"{person}'s {match.group(1)} is {answer}."
    return f"{person} said: {answer}."


class Conversation:
    """A persistent session: commands, answers to questions, pronouns, relays, stop."""

    def __init__(self, vocabulary: Vocabulary, run: Runner, *,
                 listen: Callable[[], str | None] | None = None,
                 readings: Callable[[], ReadingModel] | None = None) -> None:
        """``run(task, interrupt=...)`` carries a task out; ``listen`` returns what was
        heard while a task runs (None: nothing), asked between its steps; ``readings``
        gives the robot's current beliefs and the cost of a question, to act on the likeliest
        reading of an ambiguous command when that is worth more than asking."""
        self.vocabulary = vocabulary
        self.run = run
        self.listen = listen
        self.readings = readings
        self.discourse = Discourse()
        self.pending: ParseResult | None = None  # a command waiting for an answer
        self.heard_meanwhile: list[str] = []  # said during a task, heard next turn

    # ------------------------------------------------------------------ turns

    def hear(self, text: str) -> Turn:
        """One turn: ``text`` is a command, an answer to the open question, or "stop"."""
        said = text.strip()
        if _normalised(said) in STOP_WORDS:
            if self.pending is not None:
                self.pending = None
                return Turn(said, "cancelled", ["All right, I will not do that."])
            return Turn(said, "cancelled", ["I am not doing anything right now."])
        if self.pending is not None:
            return self._answer(said)
        return self._command(said)

    def _command(self, text: str, original: str | None = None) -> Turn:
        command = _THAT_RE.sub(r"it\2", text)  # "bring me that" after "find the cola"
        try:
            parsed = self._parse(command)
        except LanguageError as error:
            return Turn(text, "refused", [str(error)])
        if parsed.status is ParseStatus.CLARIFY:
            self.pending = parsed
            return Turn(text, "asked", [parsed.question or "What do you mean?"], parsed)
        if parsed.status is ParseStatus.REJECT:
            return Turn(text, "refused", [parsed.reason or "I cannot do that."], parsed)
        return self._carry_out(text if original is None else original, parsed)

    def _answer(self, answer: str) -> Turn:
        """Put the answer into the command that waits for it and parse that again."""
        pending = self.pending
        assert pending is not None
        self.pending = None
        candidates = _with_answer(pending, answer)
        last: Turn | None = None
        for candidate in candidates:
            try:
                parsed = self._parse(candidate)
            except LanguageError:
                continue
            if parsed:
                return self._carry_out(candidate, parsed)
            if last is None and parsed.status is ParseStatus.CLARIFY and (
                    parsed.question != pending.question):
                last = Turn(answer, "asked", [parsed.question or ""], parsed)
                self.pending = parsed
        if last is not None:
            return last
        alone = self._command(answer)  # not an answer: a new command ("bring me a beer")
        if alone.status != "asked" or alone.parse is None or alone.parse.about is None:
            return alone
        self.pending = pending  # the answer did not help: ask again
        return Turn(answer, "asked", [f"Sorry, I did not get that. {pending.question}"],
                    pending)

    def _parse(self, text: str) -> ParseResult:
        model = self.readings() if self.readings is not None else None
        return parse_command(text, self.vocabulary, history=self.discourse, readings=model)

    def _carry_out(self, command: str, parsed: ParseResult) -> Turn:
        task = Task(steps=tuple(parsed.steps), description=command)
        stopped: list[bool] = []

        def interrupt() -> bool:
            if self.listen is None:
                return False
            heard = self.listen()
            if heard is None:
                return False
            if _normalised(heard) in STOP_WORDS:
                stopped.append(True)
                return True
            self.heard_meanwhile.append(heard)
            return False

        report = self.run(task, interrupt=interrupt)
        said = ([parsed.assumed] if parsed.assumed else []) + list(report.speech)
        self._remember(report)
        if stopped:
            return Turn(command, "stopped", said, parsed, report)
        relays = self._relay(report)
        if relays:
            relayed = self.run(Task(steps=(Step("navigate", {"to": "operator"}),
                                           *(Step("say", {"text": line}) for line in relays)),
                                    description="relay what was heard"))
            said.extend(relayed.speech)
        return Turn(command, "done" if report.success else "failed", said, parsed, report)

    # ------------------------------------------------------------------ memory

    def _remember(self, report: RunReport[Any]) -> None:
        """What "it" and "them" mean after the task: the last object handled (held or
        not) and the last person found."""
        obj, state, person, last = (self.discourse.obj, self.discourse.obj_state,
                                    self.discourse.person, self.discourse.last_referent)
        for step in report.steps:
            if step.status not in {"verified", "finished"}:
                continue
            thing = step.args.get("object")
            if step.skill == "pick" and isinstance(thing, str):
                obj, state, last = thing, "held", "object"
            elif step.skill in {"give", "place"} and obj is not None:
                state = "named"
            elif step.skill == "find_object" and isinstance(thing, str):
                obj, state, last = thing, "named", "object"
            elif step.skill == "find_person":
                who = step.args.get("person") or {}
                person = dict(who) if isinstance(who, dict) else {"name": str(who)}
                last = "person"
        self.discourse = Discourse(obj, state, person, last)

    @staticmethod
    def _relay(report: RunReport[Any]) -> list[str]:
        lines = []
        for step in report.steps:
            if step.skill != "ask" or step.status != "verified" or " said: " not in step.message:
                continue
            person, answer = step.message.split(" said: ", 1)
            lines.append(relay_sentence(person, str(step.args.get("question", "")), answer))
        return lines


def _with_answer(pending: ParseResult, answer: str) -> list[str]:
    """Commands to try with the answer in them, the likeliest first."""
    original = pending.text
    reply = re.sub(r"^(i mean|i meant|the one|it is|it's|that is)\s+", "", answer.strip(),
                   flags=re.IGNORECASE).rstrip(".!?")
    candidates = []
    question = (pending.question or "").lower()
    if "how many" in question:
        number = _QUANTITY_RE.search(reply)
        amount = number.group(1) if number else reply.split()[0] if reply else ""
        if _QUANTITY_RE.search(original):
            candidates.append(_QUANTITY_RE.sub(amount, original, count=1))
    if pending.about:
        pattern = re.compile(r"\b(?:the |a |an )?" + re.escape(pending.about) + r"\b",
                             re.IGNORECASE)
        bare = re.sub(r"^(the|a|an)\s+", "", reply, flags=re.IGNORECASE)
        if pattern.search(original):
            candidates.append(pattern.sub(f"the {bare}", original, count=1))
    if _normalised(reply) in _YES:
        candidates.append(original)
    candidates.append(f"{original.rstrip('.!? ')} {reply}")
    candidates.append(f"{original.rstrip('.!? ')}, {reply}")
    return list(dict.fromkeys(candidates))
