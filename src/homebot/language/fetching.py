"""Clauses about things: take, bring, place, find an object, look at, open."""

from __future__ import annotations

from homebot.language.clauses import Clause, Item
from homebot.language.context import PLACES, Clarification, Context, Refusal, describe_item, where
from homebot.task import Step

__all__ = [
    "deliver",
    "deliver_pending",
    "direct_object",
    "fetch",
    "handle_bring",
    "handle_find_object",
    "handle_look",
    "handle_open",
    "handle_place",
    "handle_take",
    "handle_want",
    "rounds",
]

THINGS = frozenset({"object", "category", "generic", "pronoun", "person", "me", "room",
                    "placement", "door", "unknown", "ambiguous", "topic", "quote"})
_PLACE_LIKE = PLACES | {"ambiguous", "unknown"}
_SOURCE_PREPS = frozenset({"from", "on", "in", "at"})
_DEFAULT_RECIPIENT_VERBS = frozenset({"bring", "give", "hand", "pass", "serve", "hand over"})
# Verbs that mean bringing when nobody else is named: "fetch the beer" is for the speaker.
_FETCH_VERBS = frozenset({"fetch", "bring"})
_QUANTITY_ACTIONS = frozenset({"take", "bring", "place", "want"})
_MAX_ROUNDS = 6


def rounds(clause: Clause, ctx: Context) -> int:
    """How many times to carry out a clause: "bring me two drinks" is two fetches.

    A quantity larger than the things of that kind the robot knows of, or one it
    cannot know ("all the fruits"), is a question back.
    """
    counted = next((item for item in clause.items if item.quantity is not None), None)
    if counted is None:
        return 1
    if clause.action not in _QUANTITY_ACTIONS or counted.kind not in {"object", "category"}:
        raise Clarification(f"I cannot do that for {counted.quantity} "
                            f"{counted.text} at once; ask me for one thing at a time.")
    if counted.kind == "object":
        known = [str(counted.value)]
    else:
        known = ctx.vocabulary.objects_of(str(counted.value))
    plural = (ctx.vocabulary.categories.get(str(counted.value), f"{counted.value}s")
              if counted.kind == "category" else f"{counted.value}s")
    listed = ", ".join(known)
    if counted.quantity == "all" or not isinstance(counted.quantity, int):
        raise Clarification(f"How many {plural} should I bring? I know of {len(known)}: "
                            f"{listed}.")
    if counted.quantity > len(known) or counted.quantity > _MAX_ROUNDS:
        one = "only one" if len(known) == 1 else f"only {len(known)}"
        raise Clarification(f"I know of {one} {counted.value if len(known) == 1 else plural} "
                            f"here ({listed}); how many should I bring?")
    counted.definite = False  # each round fetches another one
    return counted.quantity


def deliver_pending(ctx: Context) -> None:
    """At the end of a command: a fetched object nobody else was named for goes to the
    operator ("could you fetch the beer")."""
    if ctx.bring_back and ctx.obj is not None and ctx.obj_state == "held" and not ctx.delivered:
        ctx.go_to_operator()
        ctx.emit("give", person="operator")
        ctx.delivered = True


def direct_object(clause: Clause, *, skip_me: bool = True) -> Item | None:
    """What the verb acts on: the first item said without a preposition.

    "bring me a cup": with ``skip_me`` the "me" is the recipient and "a cup" the
    object. Falls back to the first thing after "of" ("one of the apples").
    """
    bare = [item for item in clause.items if item.prep is None and item.kind in THINGS]
    if skip_me and len(bare) > 1 and bare[0].kind == "me":
        bare = bare[1:]
    if bare:
        return bare[0]
    return clause.first({"object", "category", "generic", "pronoun"}, {"of"})


def source_of(clause: Clause, target: Item | None, exclude: Item | None = None) -> Item | None:
    """Where an object is to be taken from: its locator, else a place after "from"."""
    if target is not None and target in clause.items:
        located = clause.located(target)
        if located is not None and located.kind in _PLACE_LIKE:
            return located
    for item in clause.items:
        if item is exclude or item.kind not in _PLACE_LIKE or item.prep != "from":
            continue
        return item
    for item in clause.items:  # "at the pantry, pick up the biscuits"
        if (item is not exclude and item.kind in _PLACE_LIKE and item.owner is None
                and item.prep in {"at", "in", "on"}):
            return item
    return None


def fetch(clause: Clause, ctx: Context, target: Item, source: Item | None) -> str:
    """Steps to have ``target`` in hand: navigate, find_object, pick. Returns its name."""
    refers_back = target.kind == "pronoun" or (
        ctx.obj is not None and target.kind in {"object", "category", "generic"}
        and ctx.object_of(target) == ctx.obj and ctx.obj_state != "named"
        and target.definite)
    if refers_back and source is None:
        name = ctx.object_of(target)
        if ctx.obj_state == "found":
            ctx.emit("pick", object=name)
        elif ctx.obj_state == "named":
            ctx.found_object(name, ctx.here())
            ctx.emit("pick", object=name)
        ctx.obj_state = "held"
        return name
    name = ctx.object_of(target)
    if target.kind == "category" and target.definite and source is None:
        members = ctx.vocabulary.objects_of(name)
        if len(members) > 1:
            listed = ", ".join(members[:-1]) + f" or {members[-1]}"
            raise Clarification(f"Which {name} do you mean: {listed}?", about=str(target.text),
                                options=tuple(members))
    if source is not None:
        place = ctx.place_of(source, clause, "take things from")
        ctx.go(place)
        ctx.found_object(name, where(place))
    else:
        ctx.found_object(name, ctx.here())
        if ctx.location is not None and ctx.location.kind == "me":
            ctx.location = None  # the search takes the robot away from the operator
    _superlative(clause, ctx)
    ctx.emit("pick", object=name)
    ctx.obj_state = "held"
    ctx.delivered = False
    return name


def _superlative(clause: Clause, ctx: Context) -> None:
    """"the lightest fruit on the shelf": the search chooses by that property."""
    prop = clause.first({"property"})
    if prop is not None and ctx.steps and ctx.steps[-1].skill == "find_object":
        last = ctx.steps[-1]
        ctx.steps[-1] = Step("find_object", {**last.args, "property": prop.value})


def deliver(clause: Clause, ctx: Context, recipient: Item, name: str) -> None:
    """Steps to hand ``name`` to a person or put it on a placement."""
    ctx.delivered = True
    if recipient.kind == "me" or (recipient.kind == "person"
                                  and recipient.value.get("name") == "operator"):
        ctx.go_to_operator()
        ctx.emit("give", person="operator")
        return
    if recipient.kind == "person" or (recipient.kind == "pronoun" and ctx.person is not None):
        description = ctx.person_of(recipient)
        located = clause.located(recipient) if recipient in clause.items else None
        if located is not None:
            place = ctx.place_of(located, clause, "look for people")
            ctx.go(place)
            ctx.found_person(description, where(place))
        elif (recipient.kind == "person" and description != ctx.person) or (
                recipient.kind == "pronoun" and not ctx.person_here):
            in_room = ctx.location is not None and ctx.location.kind == "room"
            ctx.found_person(description, ctx.here() if in_room else {})
        if "name" in description:
            ctx.emit("give", person=description["name"])
        else:
            ctx.emit("give")
        return
    if recipient.kind in {"room", "placement", "ambiguous"}:
        place = ctx.place_of(recipient, clause, "put things")
        if place.kind == "room":
            options = ctx.vocabulary.placements_in(str(place.value))
            raise Clarification(f"Where in the {place.value} should I put the {name}"
                                + (f": {', '.join(options)}?" if options else "?"))
        ctx.go(place)
        ctx.emit("place", placement=place.value)
        return
    if recipient.kind == "unknown":
        raise Refusal(f"I do not know anyone or any place called '{recipient.value}' here, "
                      f"so I cannot deliver the {name} there.")
    raise Refusal(f"I can hand things to people or put them on furniture, but not to "
                  f"{describe_item(recipient)}.")


def handle_take(clause: Clause, ctx: Context) -> None:
    """take / get / grasp / fetch / pick up: guide when the object is a person."""
    target = direct_object(clause, skip_me=False)
    destination = clause.first({"me", "person", "room", "placement", "ambiguous", "unknown",
                                "pronoun", "door"}, {"to"})
    recipient_me = (target is not None and target.kind == "me") or clause.first(
        {"me"}, {"for"}) is not None
    if target is not None and target.kind == "me":
        target = direct_object(clause)
    if target is None or target.kind == "me":
        raise Clarification("What should I take?")
    _refuse_non_object(target, "pick up")
    name = fetch(clause, ctx, target, source_of(clause, target, destination))
    if destination is not None:
        deliver(clause, ctx, destination, name)
    elif recipient_me:
        deliver(clause, ctx, Item("me", "operator", "me"), name)
    elif clause.verb in _FETCH_VERBS or "my" in clause.words:
        ctx.bring_back = True  # "fetch the beer", "grab my headphones"


def handle_bring(clause: Clause, ctx: Context) -> None:
    """bring / give / deliver: fetch unless held, then hand over or put down."""
    things = [item for item in clause.items
              if item.prep in {None, "of"} and item.kind in THINGS - {"me"}]
    people = [item for item in things if item.kind == "person" or (
        ctx.pronoun_means_person(item) and not ctx.person_here)]  # "bring him a beer"
    objects = [item for item in things if item.kind != "person" and item not in people]
    recipient = clause.first({"me", "person", "room", "placement", "ambiguous", "unknown",
                              "pronoun", "door"}, {"to", "for"})
    target = objects[0] if objects else None
    if target is None and ctx.obj is not None and ctx.obj_state == "held":
        target = Item("pronoun", "it", "it")
    if target is None:
        raise Clarification("What should I bring?")
    _refuse_non_object(target, "bring")
    if recipient is None:
        me = clause.first({"me"}, {None, "for"})
        recipient = me if me is not None else (people[0] if people else None)
    name = ctx.object_of(target) if target.kind == "pronoun" else None
    if not (name is not None and ctx.obj_state == "held" and name == ctx.obj):
        name = fetch(clause, ctx, target, source_of(clause, target, recipient))
    if recipient is None:
        if clause.verb not in _DEFAULT_RECIPIENT_VERBS:
            raise Clarification(f"Who should I {clause.verb} the {name} to?")
        recipient = Item("me", "operator", "me")
    deliver(clause, ctx, recipient, name)


def handle_want(clause: Clause, ctx: Context) -> None:
    """"I want a cola": bring it to the person who asked; "João would like the banana":
    bring it to João."""
    subject = next((item for item in clause.items if item.position < clause.verb_at
                    and item.kind == "person"), None)
    target = next((item for item in clause.items if item.position >= clause.verb_at
                   and item.prep is None and item.kind in THINGS - {"me"}), None) if (
        subject is not None) else direct_object(clause)
    if target is None:
        raise Clarification("What would you like me to bring you?")
    _refuse_non_object(target, "bring")
    name = fetch(clause, ctx, target, source_of(clause, target))
    deliver(clause, ctx, subject if subject is not None else Item("me", "operator", "me"), name)


def handle_place(clause: Clause, ctx: Context) -> None:
    """put / place / leave: fetch unless held, then navigate and place."""
    target = direct_object(clause)
    destination = clause.first(_PLACE_LIKE | {"me", "person"}, {"on", "in", "to", "at"})
    if destination is not None and destination.kind == "unknown":
        raise Refusal(f"There is no placement called '{destination.value}' in this home; "
                      f"I can put things on: {', '.join(ctx.vocabulary.placements)}.")
    if target is not None and target.kind in _PLACE_LIKE and target.prep is None:
        target = None
    if target is None:
        if ctx.obj is None:
            raise Clarification("What should I put there?")
        target = Item("pronoun", "it", "it")
    _refuse_non_object(target, "put down")
    source = clause.first(_PLACE_LIKE, {"from"})
    if destination is None or destination is source:
        obj = ctx.object_of(target)
        raise Clarification(f"Where should I put the {'object' if obj == 'it' else obj}?")
    name = ctx.object_of(target)
    if not (ctx.obj_state == "held" and name == ctx.obj):
        name = fetch(clause, ctx, target, source)
    deliver(clause, ctx, destination, name)


def handle_find_object(clause: Clause, ctx: Context, target: Item) -> None:
    """find / locate / look for an object or category, where said or where the robot is."""
    _refuse_non_object(target, "look for")
    name = ctx.object_of(target)
    located = clause.located(target)
    if located is None:
        located = next((item for item in clause.items if item.kind in _PLACE_LIKE
                        and item.prep in _SOURCE_PREPS and item.owner is None), None)
    if located is not None:
        place = ctx.place_of(located, clause, "look for things")
        ctx.go(place)
        ctx.found_object(name, where(place))
    else:
        ctx.found_object(name, ctx.here())


def handle_look(clause: Clause, ctx: Context) -> None:
    """look at / inspect a placement."""
    target = clause.first(_PLACE_LIKE)
    if target is None:
        raise Clarification("What should I look at?")
    place = ctx.place_of(target, clause, "look")
    ctx.go(place)
    ctx.emit("look", placement=place.value)


def handle_open(clause: Clause, ctx: Context) -> None:
    """open a door."""
    target = direct_object(clause)
    if target is None:
        raise Clarification("What should I open?")
    if target.kind == "ambiguous":
        doors = [entity.name for entity in target.value if entity.kind == "door"]
        if doors:
            raise Clarification(f"Which door do you mean: {', '.join(doors)}?")
    if target.kind != "door":
        raise Refusal(f"I can only open doors, and {describe_item(target)} is not a door.")
    ctx.emit("open_door", door=target.value)


def _refuse_non_object(target: Item, purpose: str) -> None:
    if target.kind in {"object", "category", "generic", "pronoun"}:
        return
    if target.kind == "unknown":
        raise Refusal(f"I do not know what '{target.value}' is, so I cannot {purpose} it.")
    if target.kind == "ambiguous":
        raise Refusal(f"I cannot {purpose} the {target.text}: it is furniture, not an object.")
    what = {"room": "it is a room", "placement": "it is a piece of furniture",
            "person": "it is a person", "me": "you are a person", "door": "it is a door"}
    reason = what.get(target.kind, "it is not an object")
    raise Refusal(f"I cannot {purpose} {describe_item(target)}: {reason}.")
