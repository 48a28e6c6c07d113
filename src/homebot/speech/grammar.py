"""Grammars the robot listens with: the GPSR commands of a world, yes/no, and drinks.

``command_grammar(world)`` writes, as JSGF rules, the sentence types that
``homebot.language.generator`` produces (the same verbs, topics, gestures, clothes and
sentence frames), filled with the world's rooms, placements, objects, categories and
people. Cosero's robot listens with a grammar chosen by the task's state: a yes/no
question listens for ``yes_no_grammar()``, a question about a drink for
``drink_grammar(world)``.

A ``Grammar`` is plain data (rule name -> expansion) that compiles both to JSGF for
pocketsphinx and to a regular expression, so a text can be checked against it.
"""

from __future__ import annotations

import random
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from homebot.language.generator import _GARMENTS, _GESTURES, _TOPICS, _VERBS
from homebot.language.vocabulary import phrase_tokens

__all__ = ["COMMON_NAMES", "Grammar", "command_grammar", "drink_grammar", "name_grammar",
           "words_of", "yes_no_grammar"]

_DRINK_CATEGORIES = {"drink", "drinks", "beverage", "beverages"}


def words_of(text: str) -> str:
    """The words of ``text`` as the recogniser writes them: lower case, no punctuation."""
    return " ".join(phrase_tokens(text))


def _alternatives(phrases: Iterable[str]) -> str:
    unique = sorted({words_of(phrase) for phrase in phrases} - {""})
    return " | ".join(unique) if unique else "<VOID>"


def _group_at(tokens: list[str], position: int) -> tuple[list[list[str]], int, bool]:
    """The item at ``position``: its alternatives (token lists), where the next item starts,
    and whether it is optional (``[...]``)."""
    token = tokens[position]
    if token not in "([":
        return [[token]], position + 1, False
    depth, current, choices = 0, list[str](), list[list[str]]()
    for index in range(position + 1, len(tokens)):
        item = tokens[index]
        if item in ")]" and depth == 0:
            choices.append(current)
            return choices, index + 1, token == "["
        if item == "|" and depth == 0:
            choices.append(current)
            current = []
            continue
        depth += (item in "([") - (item in ")]")
        current.append(item)
    raise ValueError(f"unbalanced {token} in a grammar rule")


_TOKEN = re.compile(r"<[\w]+>|[()\[\]|]|[^\s()\[\]|<>]+")


@dataclass(frozen=True)
class Grammar:
    """Named rules, one public: ``rules[name]`` is a JSGF expansion over words and rules."""

    name: str
    public: str
    rules: Mapping[str, str]
    # Rules whose words name things (rooms, objects, people, drinks): hypotheses that
    # differ in one of these words mean something else.
    slots: tuple[str, ...] = ()
    _compiled: dict[str, re.Pattern[str]] = field(default_factory=dict, compare=False,
                                                   repr=False)

    def jsgf(self) -> str:
        """The grammar as JSGF text for pocketsphinx."""
        lines = ["#JSGF V1.0;", f"grammar {self.name};"]
        for rule, expansion in self.rules.items():
            prefix = "public " if rule == self.public else ""
            lines.append(f"{prefix}<{rule}> = {expansion};")
        return "\n".join(lines) + "\n"

    def words(self) -> set[str]:
        """Every word the grammar can produce."""
        return {token for expansion in self.rules.values()
                for token in _TOKEN.findall(expansion)
                if token not in "()[]|" and not token.startswith("<")}

    def _regex(self, rule: str, stack: tuple[str, ...] = ()) -> str:
        if rule in stack:
            raise ValueError(f"rule <{rule}> refers to itself")
        parts = []
        for token in _TOKEN.findall(self.rules[rule]):
            if token == "<VOID>":
                parts.append("(?!)")
            elif token.startswith("<"):
                parts.append(f"(?:{self._regex(token[1:-1], (*stack, rule))})")
            elif token in "(|)":
                parts.append({"(": "(?:", "|": "|", ")": ")"}[token])
            elif token == "[":
                parts.append("(?:")
            elif token == "]":
                parts.append(")?")
            else:
                parts.append(re.escape(token) + " ")
        return "".join(parts)

    def sample(self, rng: random.Random, count: int) -> list[str]:
        """``count`` sentences of the grammar, each alternative and option chosen by ``rng``
        (the sentences a small grammar's n-gram model is trained on)."""
        return [" ".join(self._expand([f"<{self.public}>"], rng)) for _ in range(count)]

    def _expand(self, tokens: list[str], rng: random.Random) -> list[str]:
        words: list[str] = []
        position = 0
        while position < len(tokens):
            choices, position, optional = _group_at(tokens, position)
            if optional and rng.random() < 0.5:
                continue
            choice = rng.choice(choices)
            if len(choice) == 1 and choice[0].startswith("<"):
                words += self._expand(["(", *_TOKEN.findall(self.rules[choice[0][1:-1]]), ")"],
                                      rng)
            elif len(choice) == 1:
                words.append(choice[0])
            else:
                words += self._expand(choice, rng)
        return words

    def slot_words(self) -> set[str]:
        """Every word of the slot rules (``slots``)."""
        return {token for rule in self.slots for token in _TOKEN.findall(self.rules[rule])
                if token not in "()[]|" and not token.startswith("<")}

    def accepts(self, text: str) -> bool:
        """Whether the grammar can produce ``text`` (compared as ``words_of``)."""
        if "" not in self._compiled:
            self._compiled[""] = re.compile(self._regex(self.public))
        return self._compiled[""].fullmatch(words_of(text) + " ") is not None


def command_grammar(world: Any) -> Grammar:
    """The GPSR sentence types of ``homebot.language.generator`` over ``world``'s names."""
    categories = sorted({obj.category for obj in world.objects.values()})
    verbs = {f"v_{action}": _alternatives(options) for action, options in _VERBS.items()}
    rules: dict[str, str] = {
        "command": " | ".join(f"<{kind}>" for kind in (
            "go_to_loc", "take_obj", "find_obj_in_room", "find_prs_in_room", "meet_or_greet",
            "count", "tell_property", "tell_person_info", "talk_or_answer",
            "follow_or_guide", "bring_me", "meet_then_find")),
        "room": _alternatives(world.rooms),
        "placement": _alternatives(world.placements),
        "location": "<room> | <placement>",
        "object": _alternatives(world.objects),
        "category": _alternatives(categories),
        "plural": _alternatives(world.plural_of(category) for category in categories),
        "name": _alternatives(world.people),
        "article": "a | an",
        "thing": "<article> (<object> | <category>)",
        **verbs,
        "topic": _alternatives(words for words, _ in _TOPICS),
        "gesture_after": _alternatives(words for words, _, before in _GESTURES if not before),
        "gesture_before": _alternatives(words for words, _, before in _GESTURES if before),
        "posture": "sitting | standing | lying",
        "colour": "blue | yellow | black | white | red | orange | gray",
        "garment": _alternatives(words for words, _ in _GARMENTS),
        "garments": _alternatives(f"{words}s" for words, _ in _GARMENTS),
        "property": "biggest | largest | smallest | heaviest | lightest | thinnest",
        "info": "name | pose | gesture",
        "gesture_person": "<gesture_before> person | person <gesture_after>",
        "posture_person": "<posture> person",
        "clothes_person": "person wearing <article> <colour> <garment>",
        "any_person": "<gesture_person> | <posture_person> | <clothes_person>",
        "person_followup": ("<v_tell> <topic> | <v_answer> | follow them "
                            "| follow them to the <location> | <v_guide> them to the <location>"),
        "deliver": ("<v_place> it on the <placement> | <v_bring> it to me "
                    "| <v_bring> it to <name> in the <room> "
                    "| <v_bring> it to the (<gesture_person> | <posture_person>) in the <room>"),
        "object_followups": "<v_take> it and <deliver>",
        "go_to_loc": ("<v_go> the <location> then (<v_find> <thing> and <object_followups> "
                      "| <v_find> the <any_person> and <person_followup> "
                      "| meet <name> and <person_followup>)"),
        "take_obj": "<v_take> <thing> from the <placement> and <deliver>",
        "find_obj_in_room": "<v_find> <thing> in the <room> then <object_followups>",
        "find_prs_in_room": ("<v_find> <article> (<gesture_person> | <posture_person>) "
                             "in the <room> and <person_followup>"),
        "meet_or_greet": ("(<v_greet> | meet) (<name> | the <clothes_person>) in the <room> "
                          "and <person_followup>"),
        "count": ("tell me how many <plural> there are on the <placement> "
                  "| tell me how many people in the <room> are wearing <colour> <garments> "
                  "| tell me how many <posture> persons are in the <room>"),
        "tell_property": ("tell me what is the <property> (<category> | object) "
                          "on the <placement>"),
        "person_place": "in the <room> | at the <placement>",
        "tell_person_info": ("tell me the <info> of the person <person_place> "
                             "| tell the <info> of the person <person_place> "
                             "to the person at the <placement>"),
        "talk_or_answer": ("<v_tell> <topic> to the <gesture_person> in the <room> "
                           "| answer the (question | quiz) of the <gesture_person> "
                           "in the <room>"),
        "follow_or_guide": ("(<v_guide> | follow) (<name> | the <any_person>) "
                            "from the <location> to the <location>"),
        "bring_me": "<v_bring_me> <thing> from the <placement>",
        "meet_then_find": "meet <name> at the <placement> then <v_find> them in the <room>",
    }
    return Grammar("gpsr", "command", rules, slots=(
        "room", "placement", "object", "category", "plural", "name", "colour", "garment",
        "garments", "posture", "gesture_after", "gesture_before", "topic", "property",
        "info"))


def yes_no_grammar() -> Grammar:
    """What a person answers to a yes/no question."""
    return Grammar("yes_no", "answer", {
        "answer": "<yes> | <no>",
        "yes": "yes [please | sure] | yeah | sure | of course | correct | that is right "
               "| right",
        "no": "no [thanks | thank you | sorry] | nope | not now | that is wrong | wrong",
    }, slots=("yes", "no"))


def stop_grammar() -> Grammar:
    """What a person says to end being followed or guided ("stop", "you can stop now")."""
    return Grammar("stop", "answer", {
        "answer": "[ok | okay] [robot] <stop> [here | now] [please] [thank you]"
                  " | [ok | okay] we are here | that is far enough | [ok | okay] you can stop"
                  " [here | now] [thank you]",
        "stop": "stop [following me | following] | halt | wait",
    }, slots=("stop",))


#: First names a robot expects besides its household's when it asks someone their name
#: (common English first names; RoboCup@Home's guests come from such a list).
COMMON_NAMES = (
    "adam", "alex", "amelia", "angel", "anna", "axel", "ben", "charlie", "chris", "daniel",
    "david", "emma", "eric", "grace", "hannah", "jack", "jane", "james", "john", "jules",
    "julia", "kim", "laura", "leo", "lisa", "lucy", "maria", "mark", "mary", "max", "mia",
    "michael", "morgan", "noah", "olivia", "oscar", "paris", "paul", "peter", "robin", "sam",
    "sara", "simone", "sophie", "thomas", "tom", "zoe",
)


def name_grammar(world: Any) -> Grammar:
    """What a person answers to "what is your name?": their name, alone or in a sentence;
    the household's names and ``COMMON_NAMES``."""
    names = sorted({words_of(person) for person in world.people} | set(COMMON_NAMES))
    return Grammar("names", "answer", {
        "answer": "[my name is | i am | i'm | call me | it is | it's] <name> [thank you]",
        "name": _alternatives(names),
    }, slots=("name",))


def drink_grammar(world: Any) -> Grammar:
    """What a person answers to "what would you like to drink?": the world's drinks."""
    drinks = [name for name, obj in world.objects.items()
              if obj.category in _DRINK_CATEGORIES]
    return Grammar("drinks", "answer", {
        "answer": "[i would like | i want | bring me | give me] [a | an | some] <drink> "
                  "[please]",
        "drink": _alternatives(drinks),
    }, slots=("drink",))
