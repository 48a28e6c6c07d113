"""Clauses that end in words: tell, say, count, describe a person or the objects on a placement."""

from __future__ import annotations

from homebot.language.clauses import Clause, Item
from homebot.language.context import PLACES, Clarification, Context, Refusal, describe_item, where
from homebot.language.people import find_person_frame

__all__ = ["handle_count", "handle_describe", "handle_tell"]

_PLACE_LIKE = PLACES | {"ambiguous", "unknown"}
_LISTENERS = frozenset({"me", "person", "pronoun"})
_MESSAGE_VERBS = frozenset({"tell", "inform", "remind", "let"})


def report(clause: Clause, ctx: Context, exclude: Item | None = None) -> None:
    """Say the last result to whoever should hear it: a person named after "to", else the
    operator (the robot goes back first)."""
    listener = next((item for item in clause.items if item.kind in {"person", "pronoun"}
                     and item.prep == "to" and item is not exclude), None)
    if listener is not None:
        find_person_frame(clause, ctx, listener)
    else:
        ctx.go_to_operator()
    ctx.emit("say", text="$result")


def _already_reported(clause: Clause, ctx: Context) -> bool:
    """"... and tell me" after a count or description that is reported already."""
    said = bool(ctx.steps) and ctx.steps[-1].skill == "say" and ctx.steps[-1].args.get(
        "text") == "$result"
    content = [item for item in clause.items if item.kind not in {"me", "pronoun", "count"}]
    return said and not content


def handle_tell(clause: Clause, ctx: Context) -> None:
    """tell / say: a count, a property, a person's info, a talk topic or literal words."""
    if _already_reported(clause, ctx):
        return
    if clause.has("count"):
        handle_count(clause, ctx)
    elif clause.has("property"):
        handle_describe(clause, ctx)
    elif clause.has("info"):
        _describe_person(clause, ctx)
    elif clause.has("topic") or clause.has("quote"):
        _talk(clause, ctx)
    else:
        _literal(clause, ctx)


def handle_tell_me(clause: Clause, ctx: Context) -> None:
    """"let me know" / "find out" / a bare question: tell, with the operator listening."""
    if not clause.has("me"):
        clause.items.insert(0, Item("me", "operator", "me"))
        for item in clause.items[1:]:
            if item.owner is not None:
                item.owner += 1
    handle_tell(clause, ctx)


def handle_count(clause: Clause, ctx: Context) -> None:
    """count objects of a category on a placement, or people matching a description."""
    counted = next((item for item in clause.items if item.kind in {
        "category", "object", "generic", "person", "unknown", "room", "placement", "pronoun"}
        and item.prep in {None, "of"}), None)
    if counted is None:
        counted = clause.first({"category", "object", "generic", "person"})
    if counted is None:
        if _already_reported(clause, ctx):
            return
        raise Clarification("What should I count?")
    if counted.kind == "person" and "name" in counted.value:
        raise Refusal(f"{counted.value['name']} is one person; there is nothing to count.")
    if counted.kind in {"room", "placement", "unknown"}:
        what = ("I do not know what '" + str(counted.value) + "' is"
                if counted.kind == "unknown" else f"{describe_item(counted)} is not something "
                "I can count; name the objects or people to count")
        raise Refusal(f"{what}.")
    place_item = next((item for item in clause.items if item.kind in _PLACE_LIKE
                       and item is not counted and item.prep != "to"), None)
    if place_item is None:
        place = ctx.location if ctx.location is not None and ctx.location.kind in PLACES else None
        if place is None:
            raise Clarification(f"Where should I count the {_plural(ctx, counted)}?")
    else:
        place = ctx.place_of(place_item, clause, "count")
        ctx.go(place)
    if counted.kind == "person":
        ctx.emit("count", person=dict(counted.value), **where(place))
    else:
        ctx.emit("count", object=ctx.object_of(counted), **where(place))
    report(clause, ctx, exclude=counted)


def handle_describe(clause: Clause, ctx: Context) -> None:
    """the biggest / heaviest ... object (or category) on a placement."""
    prop = clause.first({"property"})
    if prop is None:
        raise Clarification("Which property do you mean: biggest, smallest, heaviest...?")
    thing = clause.first({"category", "object", "generic"})
    name = "object" if thing is None else ctx.object_of(thing)
    place_item = clause.first(_PLACE_LIKE)
    if place_item is None:
        if ctx.location is None or ctx.location.kind != "placement":
            raise Clarification(f"Where should I look for the {prop.value} {name}?")
        place = ctx.location
    else:
        place = ctx.place_of(place_item, clause, "look at objects")
        ctx.go(place)
    ctx.emit("describe", property=prop.value, object=name, **where(place))
    report(clause, ctx)


def _describe_person(clause: Clause, ctx: Context) -> None:
    info = clause.first({"info"})
    assert info is not None
    people = [item for item in clause.items if item.kind in {"person", "pronoun"}]
    subject = next((item for item in people if item.prep == "of"), None)
    if subject is None:
        subject = next((item for item in people if item.prep != "to"), None)
    if subject is not None:
        find_person_frame(clause, ctx, subject)
    if (subject is None or subject.kind == "pronoun") and ctx.person is not None and (
            len(ctx.steps) >= 2 and ctx.steps[-1].args.get("to") == "operator"
            and ctx.steps[-2].skill == "find_person"):
        ctx.steps.pop()  # "come back and tell me his pose": look at him before leaving
        ctx.location = None
    if subject is None and ctx.person is None:
        located = clause.first(_PLACE_LIKE)
        if located is None:
            raise Clarification(f"Whose {info.value} should I tell?")
        find_person_frame(clause, ctx, Item("person", {}, "the person"), located)
    ctx.emit("describe", info=info.value)
    report(clause, ctx, exclude=subject)


def _talk(clause: Clause, ctx: Context) -> None:
    listener = next((item for item in clause.items if item.kind in _LISTENERS
                     and item.prep in {"to", None}), None)
    if listener is not None and listener.kind == "me":
        if ctx.location is not None:
            ctx.go_to_operator()
    elif listener is not None:
        find_person_frame(clause, ctx, listener)
    quote = clause.first({"quote"})
    if quote is not None:
        ctx.emit("say", text=quote.value)
        return
    topic = clause.first({"topic"})
    assert topic is not None
    ctx.emit("say", info=topic.value)


def _literal(clause: Clause, ctx: Context) -> None:
    """"say good morning to Maria": the words themselves; "tell Tom that dinner is
    ready": find Tom, then say what follows "that"."""
    clause.free_text = True
    if clause.verb.split()[0] in _MESSAGE_VERBS:
        _message(clause, ctx)
        return
    listener = next((item for item in clause.items if item.kind in {"person", "pronoun"}
                     and item.prep == "to"), None)
    words = list(clause.words)
    if listener is not None:
        cut = words.index("to") if "to" in words else len(words)
        words = words[:cut]
    words = [word for word in words if word not in {"me", "that"}]
    if not words or all(not word.isalpha() for word in words):
        raise Clarification("What should I say?")
    if clause.first({"room", "placement", "object", "category"}) is not None and listener is None:
        raise Clarification(f"What should I tell about {describe_item(clause.items[0])}?")
    if listener is not None:
        find_person_frame(clause, ctx, listener)
    elif clause.has("me") and ctx.location is not None:
        ctx.go_to_operator()
    ctx.emit("say", text=" ".join(words))


def _message(clause: Clause, ctx: Context) -> None:
    """tell / inform / remind / let PERSON (know) that MESSAGE: find them, then say it.

    Without "that" there is no message to pass on: "tell me the weather forecast" is
    something the robot does not know, and it says so rather than reading the words out.
    """
    words = clause.words
    if "that" not in words:
        said = " ".join(word for word in words if word not in {"me", "us", ","})
        if not said:
            raise Clarification("What should I tell?")
        raise Refusal(f"I do not know how to tell '{said}'; I can pass on a message "
                      f"(tell NAME that ...), say the time, the day, a joke, or what I "
                      f"counted or saw.")
    cut = words.index("that")
    message = [word for word in words[cut + 1:] if word != ","]
    if not message:
        raise Clarification("What should I tell them?")
    before = [item for item in clause.items if item.position < cut]
    unknown = next((item for item in before if item.kind == "unknown"), None)
    if unknown is not None:
        raise Refusal(f"I do not know anyone called '{unknown.value}' here, so I cannot "
                      f"tell them.")
    clause.items = before  # the message's own words name no one to find or place to go
    listeners = [item for item in before if item.kind in _LISTENERS]
    if len(listeners) > 1:
        names = " and ".join(describe_item(item) for item in listeners)
        raise Clarification(f"Should I tell {names} one after the other? Please ask me "
                            f"for one person at a time.")
    if not listeners or listeners[0].kind == "me":
        ctx.go_to_operator()
    else:
        find_person_frame(clause, ctx, listeners[0])
    ctx.emit("say", text=" ".join(message))


def _plural(ctx: Context, item: Item) -> str:
    if item.kind == "category":
        return ctx.vocabulary.categories.get(str(item.value), f"{item.value}s")
    if item.kind == "person":
        return "people"
    return str(item.text)
