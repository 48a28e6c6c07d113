"""Every word accounted for: a clause is understood only when each of its parts is used.

After a clause's handler has emitted its steps, ``account_for`` checks that every content
word the person said is used by some step or is known filler. A word no step took up
("a *blue* cup"), an unknown word ("and *blorp* the fridge"), or a thing, person or place
said but left out of the steps ("go to the kitchen and cook *pasta*") makes the whole
command a question back or a refusal, never an ``ok`` that drops that part.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from homebot.language import lexicon
from homebot.language.clauses import Clause, Item
from homebot.language.context import Clarification, Context, Refusal
from homebot.task import Step

__all__ = ["account_for", "summary"]

_NAMED_KINDS = frozenset({"object", "category", "room", "placement", "door", "person",
                          "ambiguous", "topic", "property", "quote", "info"})


def account_for(clause: Clause, ctx: Context, steps: Sequence[Step]) -> None:
    """Raise ``Refusal`` or ``Clarification`` when part of ``clause`` is in no step.

    ``steps`` are all steps emitted so far (a thing named once may be used by a step
    of an earlier clause, "take the cup ... and bring it").
    """
    unsure = [word for word in clause.preverbal if word in lexicon.NEGATIONS]
    if unsure:
        raise Clarification(f"{_can_do(ctx.steps)}I cannot follow '{unsure[0]}' in a command; "
                            f"please say only what I should do.")
    checked = clause.preverbal if clause.free_text else [
        *clause.preverbal, *clause.ignored, *_unknown_words(clause)]
    impossible = [word for word in checked
                  if word.split()[0] in lexicon.IMPOSSIBLE_ACTIONS]
    if impossible:
        verb = impossible[0].split()[0]
        raise Refusal(f"I cannot {verb}: {_can_do(ctx.steps)}my skills are to go somewhere, "
                      f"find, pick up, place and bring objects, find, greet, follow and guide "
                      f"people, count, describe, answer questions and talk.")
    if checked:
        said = " ".join(dict.fromkeys(checked))
        raise Clarification(f"{_can_do(ctx.steps)}I did not understand '{said}'. "
                            f"What do you mean by it?", about=said)
    if clause.free_text:
        return  # the words themselves are said or asked
    values = _step_values(steps)
    for item in clause.items:
        if item.owner is not None and clause.items[item.owner].kind == "me":
            continue  # "bring it to me in the living room": the operator is found anyway
        if item.kind in _NAMED_KINDS and not _used(item, values, ctx):
            raise Clarification(f"{_can_do(ctx.steps)}I do not see what to do with "
                                f"{_name(item)} in that command. What should I do with it?")


def summary(steps: Sequence[Step]) -> str:
    """A few words for what the steps do: "fetch the cola", "go to the kitchen"."""
    parts: list[str] = []
    for step in steps:
        args = step.args
        if step.skill == "pick":
            parts.append(f"fetch the {args.get('object')}")
        elif step.skill == "give":
            parts.append(f"give it to {args.get('person', 'them')}"
                         if args.get("person") != "operator" else "bring it to you")
        elif step.skill == "place":
            parts.append(f"put it on the {args.get('placement')}")
        elif step.skill == "find_person":
            person = args.get("person") or {}
            parts.append(f"find {person.get('name', 'the person')}")
        elif step.skill in {"greet", "follow", "guide", "say", "ask", "count", "describe",
                            "look", "open_door", "answer_question", "where_is"}:
            parts.append(step.skill.replace("_", " "))
    if not parts:
        moves = [str(step.args.get("to")) for step in steps if step.skill == "navigate"]
        parts = [f"go to the {moves[-1]}"] if moves else []
    return ", ".join(dict.fromkeys(parts))


def _can_do(steps: Sequence[Step]) -> str:
    done = summary(steps)
    return f"I can {done}, but " if done else ""


def _unknown_words(clause: Clause) -> list[str]:
    return [str(item.value) for item in clause.items if item.kind == "unknown"]


def _step_values(steps: Iterable[Step]) -> set[str]:
    values: set[str] = set()
    for step in steps:
        values.add(step.skill)
        for key, value in step.args.items():
            values.add(key)
            _collect(value, values)
    return values


def _collect(value: Any, values: set[str]) -> None:
    if isinstance(value, dict):
        for inner in value.values():
            _collect(inner, values)
    elif isinstance(value, list | tuple):
        for inner in value:
            _collect(inner, values)
    else:
        values.add(str(value))


def _used(item: Item, values: set[str], ctx: Context) -> bool:
    vocabulary = ctx.vocabulary
    if item.kind == "person":
        name = item.value.get("name")
        return name is None or name in values or "person" in values
    if item.kind == "ambiguous":
        return any(entity.name in values for entity in item.value)
    if item.kind == "room":
        return str(item.value) in values or any(
            vocabulary.placements.get(value) == item.value for value in values)
    if item.kind == "category":
        return str(item.value) in values or any(
            vocabulary.objects.get(value) == item.value for value in values)
    if item.kind in {"topic", "quote", "info", "property"}:
        return True  # only the handlers that use them read them
    return str(item.value) in values


def _name(item: Item) -> str:
    if item.kind == "person":
        return str(item.value.get("name", "the person"))
    if item.kind == "ambiguous":
        return f"the {item.text}"
    return f"the {item.value}"
