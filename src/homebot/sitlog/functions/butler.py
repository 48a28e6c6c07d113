"""User functions of the butler's dialogue models (§9, Appendix B): the KB in conversation.

They read and update the knowledge base of Listing 3 through ``ButlerHome`` (every
update persisted in its SQLite store, with the simulated time and the reason),
and word the robot's lines (``butler_home`` hears what the user says). What the task has
gathered (the order, what the robot carries, what it saw) lives in SitLog
variables declared in ``butler.yaml``.
"""

from __future__ import annotations

import math

from homebot.knowledge import (
    AddStatement,
    ChangeValue,
    Kind,
    Literal,
    Preference,
    RemoveStatement,
    parse_statement,
)
from homebot.sitlog.functions.behaviours import member
from homebot.sitlog.functions.butler_home import (
    ButlerHome,
    hear_choice,
    hear_mood,
    hear_request,
    hear_yes_no,
    home_of,
    items_of,
)
from homebot.sitlog.interpreter import Environment
from homebot.sitlog.model import UserFunction
from homebot.sitlog.terms import Struct, Term, Text, deref, resolve

__all__ = ["ButlerHome", "user_functions"]

#: What holds of the user for one day only (Listing 3's antecedents of found_in).
_DAY_FACTS = ("bad_day", "back_from_work", "asked_comestible")


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]


def _append(env: Environment, variable: str, item: Term) -> None:
    env.set(variable, (*items_of(env, variable), item))


# ---------------------------------------------------------------- preferences (lines 1-10)

def hello(env: Environment) -> Term:
    """Line 1; a new day: what was true of the user's last day is forgotten."""
    home = home_of(env)
    for fact in _DAY_FACTS:
        if fact in [str(literal) for literal in home.kb.taxonomy.individual(
                home.user_id).properties]:
            home.update(RemoveStatement(owner=home.user_id, kind=Kind.PROPERTY,
                                        statement=parse_statement(fact)), "a new day")
    return Text(f"Hi, {home.user_name}.")


def next_choice(env: Environment) -> Term:
    """``choice(Class, A, B)`` for the next class to ask about, healthier option first."""
    home = home_of(env)
    pending = items_of(env, "ask_about")
    if not pending:
        return "none"
    env.set("ask_about", pending[1:])
    kind = str(pending[0])
    members = list(home.kb.class_extension(kind))
    if len(members) < 2 or preferred_member(home, kind) is not None:  # known already
        return next_choice(env)
    first, second = members[0], members[1]
    if home.kb.value(second, Literal("healthier_than", first)) == "yes":
        first, second = second, first
    return Struct("choice", (kind, first, second))


def after_choices(env: Environment) -> Term:
    """``more`` when preferences were asked for, else ``done`` (all known from before)."""
    return "more" if resolve(env.get("asked")) == "true" else "done"


def choice_question(env: Environment, first: str, second: str) -> Term:
    home = home_of(env)
    opening = "What" if resolve(env.get("asked")) == "true" else "Please tell me what"
    env.set("asked", "true")
    return Text(f"{opening} do you like best: {home.spoken(first)} or {home.spoken(second)}?")


def record_choice(env: Environment, kind: str, chosen: str, first: str, second: str) -> Term:
    """Store the user's preference in the KB (``to_serve``) and comment on it (lines 4, 7)."""
    home = home_of(env)
    other = second if chosen == first else first
    for weight, entity in ((1, chosen), (2, other)):
        statement = Preference((), Literal("to_serve", entity), weight)
        home.update(AddStatement(owner=kind, kind=Kind.PROPERTY, statement=statement),
                    f"{home.user_name} likes {chosen} better than {other}")
    if home.kb.value(chosen, Literal("healthier_than", other)) == "yes":
        return Text(f"Excellent! {_capital(home.spoken(chosen))} is much healthier than the "
                    f"{home.spoken(other)}!")
    if home.kb.value(other, Literal("healthier_than", chosen)) == "yes":
        return Text(f"I will recall your choice, although {home.spoken(other)} is much "
                    f"healthier than the {home.spoken(chosen)}!")
    return Text("Great! I will recall your choice!")


def thank_user(env: Environment) -> Term:
    return Text(f"Thank you, {home_of(env).user_name}.")


# ---------------------------------------------------------------- the order (lines 11-19)

def how_was_your_day(env: Environment) -> Term:
    home = home_of(env)
    home.state(home.user_id, "back_from_work", f"{home.user_name} is back from work")
    return Text(f"Hi, {home.user_name}, how was your day?")


def note_mood(env: Environment, mood: str) -> Term:
    home = home_of(env)
    if mood == "bad":
        home.state(home.user_id, "bad_day", f"{home.user_name} had a bad day")
    return Struct("mood", (mood,))


def offer_help(env: Environment, mood: str) -> Term:
    opening = "Sorry to hear that" if mood == "bad" else "Glad to hear that"
    return Text(f"{opening}; do you want me to do something for you?")


def note_request(env: Environment, items: tuple[Term, ...]) -> Term:
    home = home_of(env)
    home.state(home.user_id, "asked_comestible",
               f"{home.user_name} asked for something to eat or drink")
    env.set("requests", items)
    return Struct("request", (items,))


def preferred_member(home: ButlerHome, kind: str) -> str | None:
    """The class's member to serve first (Appendix B.1), None without a preference."""
    served = home.kb.values(kind, "to_serve")
    return str(served[0]) if served else None


def next_request(env: Environment) -> Term:
    """What to make of the next requested item: ``vague``, ``named`` or ``preferred``."""
    home = home_of(env)
    pending = items_of(env, "requests")
    if not pending:
        return "none"
    env.set("requests", pending[1:])
    item = deref(pending[0])
    if isinstance(item, Struct) and item.functor == "something":
        kind = str(deref(item.args[0]))
        favourite = preferred_member(home, kind) or next(iter(home.kb.class_extension(kind)))
        return Struct("vague", (kind, favourite))
    entity = str(item)
    preferred = preferred_member(home, home.kb.classes_of_individual(entity)[0])
    if preferred is not None and preferred != entity:
        return Struct("named", (entity, preferred))
    return Struct("preferred", (entity,))


def favourite_offer(env: Environment, kind: str, favourite: str) -> Term:
    return Text(f"Ok. I will bring you {home_of(env).spoken(favourite)}, your favorite {kind}.")


def counter_offer(env: Environment, asked: str, better: str) -> Term:
    home = home_of(env)
    return Text(f"But you like {home.spoken(better)} better than {home.spoken(asked)}! "
                f"Shall I bring you the {home.spoken(asked)}?")


def add_to_order(env: Environment, entity: str) -> Term:
    _append(env, "order", entity)
    _append(env, "to_fetch", entity)
    return Struct("order", (entity,))


def order_summary(env: Environment) -> Term:
    """Line 19: what will be brought, and the first thing to get."""
    home = home_of(env)
    order = [home.spoken(str(item)) for item in items_of(env, "order")]
    listed = " and ".join(f"the {name}" for name in order)
    return Text(f"Ok. I will bring you {listed}. I will get the {order[0]}.")


# ---------------------------------------------------------------- fetching (lines 20-25)

def next_to_fetch(env: Environment) -> Term:
    """``bring(Object)`` while something is left and a hand is free; says "I will get ..."."""
    home = home_of(env)
    pending = items_of(env, "to_fetch")
    if not pending or free_arm(env) == "none":
        return "none"
    env.set("to_fetch", pending[1:])
    entity = str(pending[0])
    if entity != str(items_of(env, "order")[0]):
        env.say(f"I will get the {home.spoken(entity)}.")
    return Struct("bring", (entity,))


def next_location(env: Environment, entity: str) -> Term:
    """``at(Shelf)``: the next preferred location not yet searched (Appendix B.2).

    When every shelf was searched once, they are searched a second time in the same
    order (a look can miss what is there); then, as a last resort, every other
    surface of the home the robot knows, nearest first; then ``none``.
    """
    home = home_of(env)
    tried = items_of(env, "tried")
    world = home.context.world
    locations = [str(location) for location in home.kb.values(entity, "loc")
                 if location in world.placements]
    for sweep in (1, 2):
        for location in locations:
            if tried.count(location) < sweep:
                if sweep == 2 and location == locations[0] and tried.count(location) == 1:
                    env.say(f"Let me look for the {home.spoken(entity)} again.")
                _append(env, "tried", location)
                return Struct("at", (location,))
    here = home.context.robot.pose().xy()
    elsewhere = sorted((name for name, placement in world.placements.items()
                        if placement.model.kind == "furniture" and name not in locations),
                       key=lambda name: math.dist(world.placements[name].approach.xy(), here))
    for location in elsewhere:
        if location not in tried:
            if not any(str(place) in elsewhere for place in tried):
                env.say(f"Let me look for the {home.spoken(entity)} elsewhere.")
            _append(env, "tried", location)
            return Struct("at", (location,))
    return "none"


def observe(env: Environment, shelf: str, seen: tuple[Term, ...], wanted: str) -> Term:
    """Note in the KB where each seen object was last seen; report a missing wanted one."""
    home = home_of(env)
    for label in (str(item) for item in seen):
        if label not in home.kb.taxonomy.individuals:
            continue
        if home.kb.value(label, Literal("last_seen", shelf)) != "yes":
            home.update(ChangeValue(owner=label, kind=Kind.PROPERTY,
                                    statement=Literal("last_seen", shelf)),
                        f"saw the {label} on {shelf}")
        if label not in items_of(env, "seen"):
            _append(env, "seen", label)
    if wanted not in [str(item) for item in seen]:
        verb = "are" if home.spoken(wanted).endswith("s") else "is"
        env.say(f"The {home.spoken(wanted)} {verb} not in {home.spoken(shelf)}.")
    return Struct("saw", (shelf, tuple(seen)))


def free_arm(env: Environment) -> Term:
    """The hand that has been free longest (``none`` when both hold something)."""
    holding = home_of(env).context.beliefs.holding
    for hand in items_of(env, "freed"):
        if holding.get(str(hand), "") is None:
            return str(hand)
    return "none"


def attempt_grab(env: Environment, entity: str, arm: str) -> Term:
    return Text(f"Attempting to grab the {home_of(env).spoken(entity)} with my {arm} arm.")


def took(env: Environment, entity: str, shelf: str, arm: str) -> Term:
    env.set("freed", tuple(h for h in items_of(env, "freed") if str(h) != arm))
    _append(env, "carried", Struct("carried", (entity, shelf, arm)))
    return Text(f"I took the {home_of(env).spoken(entity)}.")


# ---------------------------------------------------------------- delivering (lines 26-27)

def user_name(env: Environment) -> Term:
    return home_of(env).user_name


def next_user_place(env: Environment) -> Term:
    """``room(Room)``: where the user most likely is by the KB's preferences (B.2), then the
    other rooms the KB knows; twice round."""
    home = home_of(env)
    tried = items_of(env, "tried")
    likely = [str(point) for point in home.kb.values(home.user_id, "found_in")]
    others = [str(point) for point in home.kb.class_extension("point") if point not in likely]
    rooms = [home.spoken(point) for point in likely + others
             if home.spoken(point) in home.context.world.rooms]
    for sweep in (1, 2):  # people are missed at times: every room is looked at twice
        for room in rooms:
            if tried.count(room) < sweep:
                _append(env, "tried", room)
                env.set("user_room", room)
                return Struct("room", (room,))
    return "none"


def next_carried(env: Environment) -> Term:
    """``give(Object)`` for what was taken last, ``none`` when the hands are empty."""
    carried = items_of(env, "carried")
    if not carried:
        return "none"
    entity, shelf, arm = (deref(a) for a in deref(carried[-1]).args)  # type: ignore[union-attr]
    env.set("carried", carried[:-1])
    _append(env, "delivered", Struct("delivered", (entity, shelf)))
    _append(env, "freed", arm)
    return Struct("give", (entity,))


def after_delivery(env: Environment) -> Term:
    return "fetch" if items_of(env, "to_fetch") else "review"


# ---------------------------------------------------------------- the KB put right (lines 28-41)

def next_relocated(env: Environment) -> Term:
    """``relocated(O, Found, Stated)`` for a delivered object taken off its stated shelf."""
    home = home_of(env)
    pending = items_of(env, "delivered")
    while pending:
        entity, shelf = (str(deref(a)) for a in deref(pending[0]).args)  # type: ignore[union-attr]
        pending = pending[1:]
        env.set("delivered", pending)
        stated = home.stated_location(entity)
        if stated is not None and stated != shelf:
            return Struct("relocated", (entity, shelf, stated))
    return "none"


def update_question(env: Environment, entity: str, found: str, stated: str) -> Term:
    home = home_of(env)
    env.set("noticed", "true")
    name = home.spoken(entity)
    return Text(f"I found the {name} on {home.spoken(found)}, but it should be on "
                f"{home.spoken(stated)}; do you want me to change the preferred location of "
                f"{name} to {home.spoken(found)}?")


def update_location(env: Environment, entity: str, found: str) -> Term:
    home = home_of(env)
    statement = Preference((), Literal("loc", found), 1)
    home.update(AddStatement(owner=entity, kind=Kind.PROPERTY, statement=statement),
                f"{home.user_name} agreed that the {entity} belong on {found}")
    return Text("Ok. I updated my KB with your new preference.")


def keep_location(env: Environment, entity: str, stated: str) -> Term:
    home = home_of(env)
    return Text(f"Ok. I will keep {home.spoken(stated)} as the preferred location of "
                f"{home.spoken(entity)}.")


def next_misplaced(env: Environment) -> Term:
    """``misplaced(O, Where, Right)`` for an object seen off its shelf; marks it in the KB."""
    home = home_of(env)
    ordered = {str(item) for item in items_of(env, "order")}
    pending = [str(item) for item in items_of(env, "seen") if str(item) not in ordered]
    for entity in pending:
        env.set("seen", tuple(item for item in items_of(env, "seen") if str(item) != entity))
        where = home.kb.value(entity, "last_seen")
        right = home.stated_location(entity)
        if isinstance(where, str) and right is not None and where != right:
            home.state(entity, "misplaced", f"the {entity} is on {where}, not on {right}")
            return Struct("misplaced", (entity, where, right))
    return "none"


def noticed(env: Environment, entity: str) -> Term:
    also = " also" if resolve(env.get("noticed")) == "true" else ""
    env.set("noticed", "true")
    name = home_of(env).spoken(entity)
    return Text(f"I{also} noticed that the {name} is not in its right place.")


def explain(env: Environment, entity: str) -> Term:
    """Line 32: the most preferred explanation of ``misplaced`` by abduction (B.3)."""
    home = home_of(env)
    name = home.spoken(entity)
    for explanation in home.kb.explanations(entity):
        if explanation.consequent == Literal("misplaced") and explanation.antecedents:
            cause = explanation.antecedents[0]
            who = f"your {cause.value}" if cause.name == "moved_by" else str(cause)
            return Text(f"I think that the explanation for this is that the {name} was "
                        f"misplaced there by {who}.")
    return Text(f"I do not know why the {name} is there.")


def will_take_back(env: Environment, right: str) -> Term:
    return Text(f"Ok. I will take it to {home_of(env).spoken(right)}.")


def placed(env: Environment, entity: str, shelf: str, arm: str) -> Term:
    home = home_of(env)
    home.update(ChangeValue(owner=entity, kind=Kind.PROPERTY,
                            statement=Literal("last_seen", shelf)),
                f"put the {entity} on {shelf}")
    if home.kb.value(entity, "misplaced") == "yes":
        home.update(RemoveStatement(owner=entity, kind=Kind.PROPERTY,
                                    statement=parse_statement("misplaced")),
                    f"the {entity} is back on {shelf}")
    env.set("carried", tuple(c for c in items_of(env, "carried")
                             if str(deref(deref(c).args[0])) != entity))  # type: ignore[union-attr]
    _append(env, "freed", arm)
    return Struct("placed", (entity, shelf))


def put_back_line(env: Environment, entity: str) -> Term:
    return Text(f"I put the {home_of(env).spoken(entity)} on its right shelf.")


def left_there(env: Environment, entity: str) -> Term:
    env.set("left_misplaced", "true")
    return Text("Ok. I will leave it there.")


def closing_line(env: Environment) -> Term:
    if resolve(env.get("left_misplaced")) == "true":
        return Text("Some objects are not on their right shelves.")
    return Text("All the objects are placed on their right shelves.")


def user_functions() -> dict[str, UserFunction]:
    """The functions ``butler.yaml`` names, by name."""
    functions: tuple[UserFunction, ...] = (
        hear_yes_no, hear_choice, hear_mood, hear_request, hello, next_choice, after_choices,
        choice_question, record_choice, thank_user, how_was_your_day, note_mood, offer_help,
        note_request, next_request, favourite_offer, counter_offer, add_to_order, order_summary,
        next_to_fetch, next_location, observe, free_arm, attempt_grab, took, user_name,
        next_user_place, next_carried, after_delivery, next_relocated, update_question,
        update_location, keep_location, next_misplaced, noticed, explain, will_take_back, placed,
        put_back_line, left_there, closing_line, member)
    return {function.__name__: function for function in functions}
