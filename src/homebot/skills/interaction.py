"""Skills that talk: say, ask, greet, answer_question."""

from __future__ import annotations

from collections.abc import Mapping
from datetime import timedelta
from typing import Any

from homebot.skills.places import people_in_view, person_name
from homebot.skills.skill import ErrorCode, Outcome, Skill, SkillContext, speak
from homebot.skills.wording import be, object_is_at, place_in

__all__ = ["AnswerQuestion", "Ask", "Greet", "Say", "WhereIs", "answer_about_home",
           "talk_about", "where_sentence"]

# in English whatever the process's locale (strftime's %A and %B follow the locale)
_DAYS = ("Monday", "Tuesday", "Wednesday", "Thursday", "Friday", "Saturday", "Sunday")
_MONTHS = ("January", "February", "March", "April", "May", "June", "July", "August",
           "September", "October", "November", "December")


def _ordinal(day: int) -> str:
    suffix = "th" if 11 <= day % 100 <= 13 else {1: "st", 2: "nd", 3: "rd"}.get(day % 10, "th")
    return f"{day}{suffix}"


def talk_about(context: SkillContext, topic: str) -> str:
    """A sentence on a GPSR talk topic; time and day come from the simulated clock, counted
    from the run's start date and time (``context.started_at``)."""
    now = context.started_at + timedelta(seconds=context.robot.now())
    topic_key = topic.lower()
    if "time" in topic_key:
        return f"It is {now:%H:%M}."
    if "tomorrow" in topic_key:
        return f"Tomorrow is {_DAYS[(now + timedelta(days=1)).weekday()]}."
    if "day" in topic_key and "month" in topic_key:
        return f"Today is the {_ordinal(now.day)} of {_MONTHS[now.month - 1]}."
    if "day" in topic_key:
        return f"Today is {_DAYS[now.weekday()]}."
    if "joke" in topic_key:
        return "Why did the robot go on holiday? It needed to recharge."
    if "yourself" in topic_key or "name" in topic_key:
        return "I am homebot, a service robot for the home."
    if "team" in topic_key:
        return "My team is homebot."
    return topic


def answer_about_home(context: SkillContext, question: str) -> str:
    """Answer a question about the home from what the robot believes."""
    words = question.lower().rstrip("?").split()
    text = " ".join(words)
    world = context.world
    if "how many rooms" in text:
        return f"There are {len(world.rooms)} rooms."
    if "how many people" in text:
        return f"{len(world.people)} people live here."
    if text.startswith("where is") or text.startswith("where are"):
        thing = " ".join(w for w in words[2:] if w not in {"the", "a", "an"})
        where = context.beliefs.object_at.get(thing)
        if where and where in world.placements:
            return object_is_at(thing, place_in(world, where))
        if where and where.startswith("hand:"):
            return f"I am holding the {thing}."
        return f"I do not know where the {thing} {be(thing)}."
    if "time" in text or "day" in text:
        return talk_about(context, text)
    return "I am sorry, I do not know the answer."


class Say(Skill):
    """Say literal text, a talk topic (``info``), ``$result`` (the last count or description)
    or ``$answer`` (what the last ``ask`` heard)."""

    name = "say"
    optional = ("text", "info")

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        if args.get("info"):
            text = talk_about(context, str(args["info"]))
        else:
            text = str(args.get("text", ""))
            if text == "$result":
                text = str(context.bindings.get("result", "I have nothing to report."))
            elif text == "$answer":  # what the last ``ask`` heard
                answer = context.bindings.get("answer")
                text = f"The answer was: {answer}." if answer else "I got no answer."
        if not text:
            return Outcome.failed(ErrorCode.UNKNOWN_TARGET, "I have nothing to say")
        speak(context, text)
        return Outcome.finished(text, text=text)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        return Outcome.verified(finished.message, text=finished.data["text"])


class Ask(Skill):
    """Ask a person (or the person last found) a question. Binds ``answer``."""

    name = "ask"
    required = ("question",)
    optional = ("person",)
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to ask")
        question = str(args["question"])
        context.events.record("speech", text=question)
        answer = context.robot.ask(person, question)
        return Outcome.finished(question, person=person, answer=answer)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        answer = finished.data["answer"]
        if not answer:
            return Outcome.aborted(ErrorCode.NO_ANSWER, f"{finished.data['person']} did not answer")
        context.bindings["answer"] = answer
        context.events.record("heard", person=finished.data["person"], text=answer)
        return Outcome.verified(f"{finished.data['person']} said: {answer}", answer=answer)


class Greet(Skill):
    """Greet the person last found (or the named person) by name."""

    name = "greet"
    optional = ("person",)

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to greet")
        text = f"Hello {person}, nice to meet you."
        speak(context, text)
        return Outcome.finished(text, person=person)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        person = finished.data["person"]
        if any(seen.name == person for seen in people_in_view(context)):
            return Outcome.verified(f"greeted {person}")
        return Outcome.aborted(ErrorCode.LOST_PERSON, f"{person} is not here to be greeted")


class AnswerQuestion(Skill):
    """Ask the person last found for their question and answer it from the robot's beliefs."""

    name = "answer_question"
    optional = ("person",)
    retries = 1

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        person = person_name(context, args.get("person"))
        if person is None:
            return Outcome.failed(ErrorCode.NO_PERSON, "I have nobody to answer")
        question = context.robot.ask(person, "What is your question?")
        return Outcome.finished(person=person, question=question)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        question = finished.data["question"]
        if not question:
            return Outcome.aborted(ErrorCode.NO_ANSWER, f"{finished.data['person']} asked nothing")
        answer = answer_about_home(context, question)
        speak(context, answer)
        return Outcome.verified(answer, question=question, answer=answer)


def where_sentence(context: SkillContext, thing: str) -> str:
    """Where the robot believes ``thing`` (an object or a category) is, and why it thinks so:
    it saw it there itself, it holds it, or the home's map says so."""
    world = context.world
    names = [thing] if thing in world.objects else [
        name for name, obj in world.objects.items()
        if thing in (obj.category, world.plural_of(obj.category))]
    for name in names:
        where = context.beliefs.object_at.get(name)
        if where and where.startswith("hand:"):
            return f"I am holding the {name}."
        if where and where in world.placements:
            source = ("I saw it there myself" if name in context.beliefs.seen
                      else "that is where the map of the home says it is kept")
            return f"{object_is_at(name, place_in(world, where))[:-1]}; {source}."
    return f"I do not know where the {thing} {be(thing)}: I have not seen it anywhere."


class WhereIs(Skill):
    """Say where an object is believed to be, from the robot's beliefs, with their source.

    Binding ``result``: the sentence (reported by a following ``say``).
    """

    name = "where_is"
    required = ("object",)

    def execute(self, context: SkillContext, args: Mapping[str, Any]) -> Outcome:
        text = where_sentence(context, str(args["object"]))
        return Outcome.finished(text, result=text)

    def monitor(self, context: SkillContext, args: Mapping[str, Any],
                finished: Outcome) -> Outcome:
        context.bindings["result"] = finished.data["result"]
        return Outcome.verified(finished.message, result=finished.data["result"])
