"""The discourse context of one parse: steps so far, where the robot is, what "it" is."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from homebot.language.clauses import Clause, Item
from homebot.language.vocabulary import Vocabulary
from homebot.task import Step

__all__ = ["Clarification", "Context", "Discourse", "Refusal", "describe_item"]

PLACES = frozenset({"room", "placement"})


class Clarification(Exception):
    """The command misses something; ``question`` asks for it.

    ``about`` is the words of the command the question is about ("table" in "which
    table do you mean"), which an answer replaces; None when the answer adds to it.
    """

    def __init__(self, question: str, about: str | None = None,
                 options: tuple[str, ...] = ()) -> None:
        super().__init__(question)
        self.question = question
        self.about = about
        self.options = options  # the readings asked about ("kitchen table", "coffee table")


@dataclass(frozen=True)
class Discourse:
    """What earlier commands of a conversation left to refer back to: the object "it"
    means (and whether the robot holds it) and the person "them" means."""

    obj: str | None = None
    obj_state: str = "named"
    person: dict[str, str] | None = None
    last_referent: str | None = None


class Refusal(Exception):
    """The command cannot be done; ``reason`` says why."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


def describe_item(item: Item) -> str:
    """How to name an item back to the person ("the kitchen", "Maria", "it")."""
    if item.kind == "person":
        return _describe_person(item.value)
    if item.kind == "me":
        return "you"
    if item.kind == "ambiguous":
        return f"the {item.text}"
    if item.kind in {"pronoun", "quote"}:
        return str(item.text)
    return f"the {item.value}"


def _describe_person(description: dict[str, str]) -> str:
    if "name" in description:
        return description["name"]
    parts = [f"{key} {value.replace('_', ' ')}" for key, value in description.items()]
    return "the person" + (f" ({', '.join(parts)})" if parts else "")


@dataclass
class Context:
    """What the parse knows while reading clause after clause.

    ``location`` is where the robot will be (a room or placement item, "operator"
    or a person); ``obj`` is what "it" refers to and ``obj_state`` whether it was
    only named, found or is held; ``person`` is the description of the last person
    found ("them").
    """

    vocabulary: Vocabulary
    steps: list[Step] = field(default_factory=list)
    location: Item | None = None
    obj: str | None = None
    obj_state: str = "named"
    person: dict[str, str] | None = None
    last_referent: str | None = None
    delivered: bool = False  # the object last fetched was handed over or put down
    person_here: bool = True  # the person "them" means was found in this command
    bring_back: bool = False  # "fetch the beer": bring it to the operator if nobody else

    # ------------------------------------------------------------------ steps

    def emit(self, skill: str, **args: Any) -> None:
        self.steps.append(Step(skill, args))

    def go(self, place: Item) -> None:
        """Navigate to a room or placement unless the last step already did."""
        target = place.value
        if self.steps and self.steps[-1] == Step("navigate", {"to": target}):
            return
        self.emit("navigate", to=target)
        self.location = place

    def go_to_operator(self) -> None:
        if self.location is not None and self.location.kind == "me":
            return
        self.emit("navigate", to="operator")
        self.location = Item("me", "operator", "me")

    def here(self) -> dict[str, str]:
        """The location arguments of where the robot is, when that is a place."""
        return where(self.location) if self.location is not None else {}

    def found_person(self, description: dict[str, str], place: dict[str, str]) -> None:
        self.emit("find_person", person=dict(description), **place)
        self.person = dict(description)
        self.person_here = True
        self.last_referent = "person"

    def found_object(self, name: str, place: dict[str, str]) -> None:
        self.emit("find_object", object=name, **place)
        self.obj, self.obj_state, self.last_referent = name, "found", "object"

    # ------------------------------------------------------------------ references

    def object_of(self, item: Item) -> str:
        """The object value of an item: a name, a category, "object", or what "it" is."""
        if item.kind in {"object", "category"}:
            return str(item.value)
        if item.kind == "generic":
            return "object"
        if item.kind == "pronoun":
            if self.obj is None:
                raise Clarification(f"What do you mean by '{item.text}'? Name the object.",
                                    about=str(item.text))
            return self.obj
        raise Refusal(_not_an_object(item))

    def person_of(self, item: Item) -> dict[str, str]:
        """The person description of an item; pronouns refer to the last person found."""
        if item.kind == "person":
            return dict(item.value)
        if item.kind == "pronoun":
            if self.person is None:
                raise Clarification(f"Who do you mean by '{item.text}'?", about=str(item.text))
            return dict(self.person)
        if item.kind == "me":
            return {"name": "operator"}
        raise Refusal(_not_a_person(item))

    def pronoun_means_person(self, item: Item) -> bool:
        """Whether a pronoun refers to the last person rather than the last object."""
        if item.kind != "pronoun" or self.person is None:
            return False
        if self.obj is None or self.obj_state != "held":
            return self.last_referent == "person" or self.obj is None
        return False

    # ------------------------------------------------------------------ places

    def place_of(self, item: Item, clause: Clause, purpose: str) -> Item:
        """A room or placement item, with "the table" narrowed by a room if possible."""
        if item.kind in PLACES:
            return item
        if item.kind == "ambiguous":
            return self._narrow(item, clause)
        if item.kind == "unknown":
            raise Refusal(f"I do not know any place called '{item.value}' in this home, "
                          f"so I cannot {purpose} there.")
        raise Refusal(f"I cannot {purpose} {describe_item(item)}: "
                      f"{_what_it_is(item)}, not a room or a piece of furniture.")

    def _narrow(self, item: Item, clause: Clause) -> Item:
        candidates = [entity for entity in item.value if entity.kind in PLACES]
        rooms = [other.value for other in clause.items if other.kind == "room"]
        if not rooms and self.location is not None and self.location.kind == "room":
            rooms = [self.location.value]
        if not rooms and self.location is not None and self.location.kind == "placement":
            rooms = [self.vocabulary.placements[self.location.value]]
        narrowed = [e for e in candidates
                    if self.vocabulary.placements.get(e.name) in rooms] if rooms else []
        if len(narrowed) == 1:
            return Item("placement", narrowed[0].name, item.text, item.prep, item.definite)
        options = narrowed or candidates
        names = ", ".join(entity.name for entity in options[:-1])
        raise Clarification(f"Which {item.text} do you mean: {names} or {options[-1].name}?",
                            about=str(item.text),
                            options=tuple(entity.name for entity in options))


def where(item: Item | None) -> dict[str, str]:
    """``{"room": ...}`` or ``{"placement": ...}`` for a place item, else nothing."""
    if item is None or item.kind not in PLACES:
        return {}
    return {str(item.kind): str(item.value)}


def _what_it_is(item: Item) -> str:
    kinds = {"room": "it is a room", "placement": "it is a piece of furniture",
             "object": "it is an object", "category": "it is a kind of object",
             "person": "it is a person", "me": "you are a person", "door": "it is a door",
             "generic": "it is an object", "topic": "it is something to say",
             "unknown": "I do not know it"}
    return kinds.get(item.kind, "it is not a thing")


def _not_an_object(item: Item) -> str:
    return f"I can only handle objects, and {describe_item(item)} is not one ({_what_it_is(item)})."


def _not_a_person(item: Item) -> str:
    if item.kind == "unknown":
        return f"I do not know anyone called '{item.value}' here."
    return (f"That only works with people, and {describe_item(item)} is not a person "
            f"({_what_it_is(item)}).")
