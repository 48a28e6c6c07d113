"""The butler's home as its functions see it (KB store, skills, user) and how it hears speech."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from types import MappingProxyType

from homebot.errors import DialogueError
from homebot.knowledge import ANY, AddStatement, Kind, KnowledgeBase, Update, parse_statement
from homebot.knowledge.store import KnowledgeStore
from homebot.sitlog.interpreter import Environment
from homebot.sitlog.terms import Struct, Term, Text, resolve
from homebot.skills import SkillContext
from homebot.text import fold

__all__ = ["ButlerHome", "hear_choice", "hear_mood", "hear_request", "hear_yes_no", "home_of",
           "items_of"]

_YES = frozenset({"yes", "yeah", "yep", "sure", "ok", "okay", "please", "right"})
_NO = frozenset({"no", "nope", "not"})
_CLASS_WORDS = MappingProxyType({"drink": "drink", "drinks": "drink", "eat": "food",
                                 "food": "food"})


@dataclass
class ButlerHome:
    """What the butler's functions work with: the KB store, the skills, who the user is."""

    store: KnowledgeStore
    context: SkillContext
    user_name: str = "Luis"
    user_id: str = "user"
    spoken_names: dict[str, str] = field(default_factory=lambda: {"bisquits": "biscuits"})
    updates: list[str] = field(default_factory=list)

    @property
    def kb(self) -> KnowledgeBase:
        return self.store.kb

    def update(self, update: Update, why: str) -> None:
        """Apply and persist one KB update (simulated time, reason)."""
        self.store.apply(update, when=self.context.robot.now(), why=why)
        self.updates.append(f"{update} ({why})")
        self.context.events.record("kb.update", update=update.to_dict(), why=why)

    def state(self, owner: str, literal: str, why: str) -> None:
        """Add the property ``literal`` to ``owner`` unless it holds already (persisted)."""
        if self.kb.value(owner, literal) != "yes":
            self.update(AddStatement(owner=owner, kind=Kind.PROPERTY,
                                     statement=parse_statement(literal)), why)

    def spoken(self, entity: str) -> str:
        """How the robot names an object or place: the KB's ``name``, else its id."""
        if entity in self.spoken_names:
            return self.spoken_names[entity]
        if entity in self.kb.taxonomy.individuals:
            name = self.kb.value(entity, "name")
            if isinstance(name, str) and name not in ("unknown", "yes", "no"):
                return name
        if entity in self.context.world.placements:
            return f"the {entity.replace('_', ' ')}"  # a surface the KB has no name for
        return entity.replace("_", " ")

    def stated_location(self, entity: str) -> str | None:
        """Where the KB says an object belongs: its first unconditional ``loc`` default."""
        for preference in self.kb.preferences(entity):
            consequent = preference.consequent
            if consequent.name == "loc" and not preference.antecedents and (
                    isinstance(consequent.value, str) and consequent.value != ANY):
                return consequent.value
        return None

    def comestibles(self) -> list[str]:
        return list(self.kb.class_extension("comestible"))


def home_of(env: Environment) -> ButlerHome:
    home = env.application
    if not isinstance(home, ButlerHome):
        raise DialogueError(f"{env.place}: the butler's dialogue models need the butler's home "
                            "(its KB and robot); run them with homebot scenario butler")
    return home


def _words(text: Term) -> list[str]:
    """The words heard, folded (``homebot.text.fold``): "Crème" is heard as "creme"."""
    return re.findall(r"(?:[^\W\d_]|')+", fold(str(resolve(text))))


def _mentioned(home: ButlerHome, words: list[str]) -> list[str]:
    """Objects named in the words, in order (spoken names and ids both count, folded)."""
    names = {fold(home.spoken(entity)): entity for entity in home.comestibles()}
    names.update({fold(entity): entity for entity in home.comestibles()})
    return [names[word] for word in words if word in names]


def items_of(env: Environment, variable: str) -> tuple[Term, ...]:
    value = resolve(env.get(variable))
    return value if isinstance(value, tuple) else ()


# ---------------------------------------------------------------- interpreters of speech

def hear_yes_no(env: Environment, heard: Term, expectations: tuple[Term, ...]) -> Term:
    """``yes`` or ``no`` from the first word that says it."""
    for word in _words(heard):
        if word in _YES:
            return "yes"
        if word in _NO:
            return "no"
    return Struct("unclear", (Text(str(resolve(heard))),))


def hear_choice(env: Environment, heard: Term, expectations: tuple[Term, ...]) -> Term:
    """``chose(Object)``: the object the user says they like."""
    mentioned = _mentioned(home_of(env), _words(heard))
    return Struct("chose", (mentioned[-1],)) if mentioned else hear_yes_no(env, heard, ())


def hear_mood(env: Environment, heard: Term, expectations: tuple[Term, ...]) -> Term:
    """``mood(bad)`` or ``mood(good)`` from how the user says their day was."""
    words = set(_words(heard))
    if words & {"bad", "awful", "terrible", "horrible", "tiring"}:
        return Struct("mood", ("bad",))
    return Struct("mood", ("good",))


def hear_request(env: Environment, heard: Term, expectations: tuple[Term, ...]) -> Term:
    """``request([...])``: named objects and ``something(Class)`` for vague ones."""
    home = home_of(env)
    text = str(resolve(heard)).lower()
    items: list[Term] = []
    for part in re.split(r",|\band\b", text):
        words = _words(part)
        named = _mentioned(home, words)
        if named:
            items.extend(named)
            continue
        classes = [_CLASS_WORDS[w] for w in words if w in _CLASS_WORDS]
        if classes:
            items.append(Struct("something", (classes[0],)))
    return Struct("request", (tuple(items),)) if items else hear_yes_no(env, heard, ())
