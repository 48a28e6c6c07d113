"""Clauses about people and moving: go, find or meet someone, greet, follow, guide, answer."""

from __future__ import annotations

from homebot.language.clauses import Clause, Item
from homebot.language.context import PLACES, Clarification, Context, Refusal, describe_item, where
from homebot.language.fetching import direct_object

__all__ = ["find_person_frame", "handle_answer", "handle_ask", "handle_follow", "handle_go",
           "handle_greet", "handle_guide", "handle_meet", "handle_return", "person_target",
           "wants_person"]

_PLACE_LIKE = PLACES | {"ambiguous", "unknown"}
_AT_PREPS = frozenset({"in", "at", "from", "on"})


def wants_person(item: Item | None, ctx: Context) -> bool:
    """Whether an item names a person (or a pronoun that refers to one)."""
    if item is None:
        return False
    return item.kind in {"person", "me"} or ctx.pronoun_means_person(item)


def person_target(clause: Clause, ctx: Context) -> Item | None:
    """The person a clause is about: its direct object, else the first person named."""
    target = direct_object(clause, skip_me=False)
    if target is not None and (wants_person(target, ctx) or target.kind == "pronoun"):
        return target
    people = clause.first({"person"})
    return people if people is not None else target


def find_person_frame(clause: Clause, ctx: Context, target: Item,
                      location: Item | None = None) -> dict[str, str]:
    """Navigate to where the person is said to be and find them; their description.

    A pronoun for the person last found needs no new search unless a place is given.
    """
    if target.kind not in {"person", "pronoun", "me"}:
        _refuse_non_person(target)
    description = ctx.person_of(target)
    if location is None and target in clause.items:
        location = clause.located(target)
    if location is None and target.kind != "pronoun":
        location = next((item for item in clause.items if item.kind in _PLACE_LIKE
                         and item.prep in _AT_PREPS and item.owner is None), None)
    if target.kind == "me" and location is None:
        return description
    if location is not None:
        place = ctx.place_of(location, clause, "look for people")
        ctx.go(place)
        ctx.found_person(description, where(place))
    elif target.kind != "pronoun":
        ctx.found_person(description, ctx.here())
    return description


def handle_go(clause: Clause, ctx: Context) -> None:
    """go / navigate / head to a room, placement, person or the operator."""
    target = clause.first(_PLACE_LIKE | {"me", "person", "object", "category", "door"},
                          {"to", None, "in", "at"})
    if target is None and "here" in clause.words:
        ctx.go_to_operator()  # "come here", "come over here"
        return
    if target is None:
        raise Clarification("Where should I go?")
    if target.kind == "me":
        ctx.go_to_operator()
        return
    if target.kind == "person":
        if clause.located(target) is not None:
            find_person_frame(clause, ctx, target)
        elif "name" in target.value:
            ctx.emit("navigate", to=target.value["name"])
            ctx.person, ctx.last_referent = dict(target.value), "person"
            ctx.location = target
        else:
            find_person_frame(clause, ctx, target)
        return
    if target.kind in {"object", "category"}:
        raise Refusal(f"I can go to rooms, furniture and people, not to {describe_item(target)}; "
                      f"ask me to bring it or to find it instead.")
    if target.kind == "door":
        raise Refusal(f"I go through doors on my own; name the room behind the {target.value}.")
    ctx.go(ctx.place_of(target, clause, "go"))


def handle_return(clause: Clause, ctx: Context) -> None:
    """come back / return: to the operator unless a place is named."""
    target = clause.first(_PLACE_LIKE, {"to", None})
    if target is None:
        ctx.go_to_operator()
    else:
        ctx.go(ctx.place_of(target, clause, "go"))


def handle_find_person(clause: Clause, ctx: Context, target: Item) -> None:
    find_person_frame(clause, ctx, target)


def handle_meet(clause: Clause, ctx: Context) -> None:
    """meet NAME [in/at PLACE]."""
    target = person_target(clause, ctx)
    if target is None:
        raise Clarification("Whom should I meet?")
    find_person_frame(clause, ctx, target)


def handle_greet(clause: Clause, ctx: Context) -> None:
    """greet / salute / say hello to / introduce yourself to someone."""
    target = person_target(clause, ctx)
    if target is not None and target.kind not in {"person", "pronoun", "me"}:
        _refuse_non_person(target)
    if target is not None:
        find_person_frame(clause, ctx, target)
    ctx.emit("greet")


def handle_follow(clause: Clause, ctx: Context) -> None:
    """follow someone [from PLACE] [to PLACE]."""
    target = person_target(clause, ctx)
    if target is not None and target.kind not in {"person", "pronoun", "me"}:
        _refuse_non_person(target)
    thing = clause.first({"object", "category"}, {"to"})
    if thing is not None:
        raise Refusal(f"I can follow people to rooms and furniture, not to "
                      f"{describe_item(thing)}.")
    destination = clause.first(_PLACE_LIKE, {"to"})
    if target is not None and target.kind != "me":
        source = clause.first(_PLACE_LIKE, {"from", "at", "in", "on"})
        find_person_frame(clause, ctx, target, source if source is not destination else None)
    if destination is not None:
        place = ctx.place_of(destination, clause, "follow anyone")
        ctx.emit("follow", to=place.value)
    else:
        ctx.emit("follow")


def handle_guide(clause: Clause, ctx: Context) -> None:
    """guide / escort / lead / take someone [from PLACE] to PLACE."""
    target = person_target(clause, ctx)
    if target is not None and target.kind not in {"person", "pronoun", "me"}:
        _refuse_non_person(target)
    destination = clause.first(_PLACE_LIKE | {"object", "category"}, {"to"})
    if destination is None:
        who = "them" if target is None or target.kind == "pronoun" else describe_item(target)
        raise Clarification(f"Where should I guide {who}?")
    if destination.kind in {"object", "category"}:
        raise Refusal(f"I can guide people to rooms and furniture, not to "
                      f"{describe_item(destination)}.")
    place = ctx.place_of(destination, clause, "guide anyone")
    if target is not None and target.kind != "me":
        source = clause.first(_PLACE_LIKE, {"from", "at", "in", "on"})
        find_person_frame(clause, ctx, target, source)
    ctx.emit("guide", to=place.value)


def handle_answer(clause: Clause, ctx: Context) -> None:
    """answer a question, or the question of someone."""
    target = clause.first({"person", "pronoun"})
    if target is not None:
        find_person_frame(clause, ctx, target)
    ctx.emit("answer_question")


def handle_ask(clause: Clause, ctx: Context) -> None:
    """ask someone a question ("ask Maria her name", ask the waving person "...")."""
    target = person_target(clause, ctx)
    question = _question(clause)
    person = None
    if target is not None and target.kind != "me":
        description = find_person_frame(clause, ctx, target)
        person = description.get("name")
    elif target is not None:
        ctx.go_to_operator()
        person = "operator"
    args = {"question": question} if person is None else {"question": question, "person": person}
    ctx.emit("ask", **args)


def _question(clause: Clause) -> str:
    quote = clause.first({"quote"})
    if quote is not None:
        return str(quote.value)
    info = clause.first({"info"})
    if info is not None:
        return f"what is your {info.value}"
    topic = clause.first({"topic"})
    if topic is not None:
        return str(topic.value)
    clause.free_text = True  # the question is the clause's own words
    anchors = [item for item in clause.items
               if (item.kind in PLACES | {"ambiguous", "person", "me"})
               or (item.kind == "pronoun" and item.prep is None and item is clause.items[0])]
    start = max((item.position for item in anchors), default=-1) + 1
    words = clause.words[start:]
    while words and words[0] in {"to", "for", "if", "whether", "about", ","}:
        words = words[1:]
    if not words:
        raise Clarification("What should I ask?")
    return " ".join(direct_question(words))


_AUXILIARIES = frozenset({"is", "are", "would", "will", "can", "could", "does", "do", "did",
                          "was", "were", "has", "have", "should"})
_TO_YOU = {"she": "you", "he": "you", "they": "you", "her": "your", "his": "your",
           "their": "your", "him": "you", "them": "you", "hers": "yours", "theirs": "yours",
           "herself": "yourself", "himself": "yourself", "themselves": "yourself"}
_WH = frozenset({"what", "where", "which", "who", "how", "when", "why", "whose"})


def direct_question(words: list[str]) -> list[str]:
    """The reported question turned to the person: "what her favourite food is" ->
    "what is your favourite food"; "where she is from" -> "where are you from"."""
    words = " ".join(words).split()
    if not words or words[0] not in _WH:
        return words
    rest = [_TO_YOU.get(word, word) for word in words[1:]]
    aux_at = next((index for index, word in enumerate(rest) if word in _AUXILIARIES), None)
    if aux_at is None or aux_at == 0 or ("you" not in rest[:aux_at] and "your" not in (
            " ".join(rest[:aux_at]).split())):
        return [words[0], *rest]
    aux = rest[aux_at]
    subject = rest[:aux_at]
    if subject == ["you"] and aux == "is":
        aux = "are"
    elif subject == ["you"] and aux in {"does", "has", "was"}:
        aux = {"does": "do", "has": "have", "was": "were"}[aux]
    return [words[0], aux, *subject, *rest[aux_at + 1:]]


def _refuse_non_person(target: Item) -> None:
    if target.kind == "unknown":
        raise Refusal(f"I do not know anyone called '{target.value}' here.")
    raise Refusal(f"That only works with people, and {describe_item(target)} is not a person.")
