"""Questions the robot answers: what is on or in a place, where a thing is, who someone is.

"what's in the fridge" goes and looks (``look``, whose result is reported); "where is the
cola" answers from what the robot believes (``where_is``, which says where the belief
comes from); "describe the person in the kitchen" finds them and describes them.
"""

from __future__ import annotations

from homebot.language.clauses import Clause, Item
from homebot.language.context import PLACES, Clarification, Context, Refusal, describe_item
from homebot.language.people import find_person_frame
from homebot.language.reporting import report

__all__ = ["handle_contents", "handle_describe_person", "handle_where"]

_PLACE_LIKE = PLACES | {"ambiguous", "unknown"}


def handle_contents(clause: Clause, ctx: Context) -> None:
    """what is on / in PLACE (or "what's inside" where the robot is): look, then report."""
    target = clause.first(_PLACE_LIKE)
    if target is None:
        if ctx.location is None or ctx.location.kind != "placement":
            raise Clarification("Which place should I look at?")
        place = ctx.location
    else:
        place = ctx.place_of(target, clause, "look")
        if place.kind == "room":
            options = ctx.vocabulary.placements_in(str(place.value))
            raise Clarification(f"Where in the {place.value} should I look"
                                + (f": {', '.join(options)}?" if options else "?"))
        ctx.go(place)
    if not (ctx.steps and ctx.steps[-1].skill == "look"
            and ctx.steps[-1].args.get("placement") == place.value):
        ctx.emit("look", placement=place.value)  # "have a look at the desk and tell me ..."
    report(clause, ctx)


def handle_where(clause: Clause, ctx: Context) -> None:
    """where is OBJECT: answered from what the robot believes, then said to the operator."""
    target = next((item for item in clause.items
                   if item.kind in {"object", "category", "pronoun", "unknown", "person",
                                    "placement", "room", "ambiguous"}), None)
    if target is None:
        raise Clarification("Where is what? Name the object.")
    if target.kind == "unknown":
        raise Refusal(f"I do not know what '{target.value}' is, so I cannot say where it is.")
    if target.kind in {"person", "placement", "room", "ambiguous"}:
        raise Refusal(f"I can say where objects are, not {describe_item(target)}.")
    ctx.emit("where_is", object=ctx.object_of(target))
    report(clause, ctx)


def handle_describe_person(clause: Clause, ctx: Context) -> None:
    """describe PERSON / the person in ROOM: find them, describe them, report."""
    target = clause.first({"person", "pronoun", "me"})
    if target is None:
        located = clause.first(_PLACE_LIKE)
        if located is None:
            thing = clause.first({"object", "category"})
            if thing is not None:
                raise Refusal(f"I can describe people, and the objects on a piece of "
                              f"furniture, but not {describe_item(thing)} on its own.")
            raise Clarification("Whom should I describe?")
        find_person_frame(clause, ctx, Item("person", {}, "the person"), located)
    elif target.kind == "me":
        raise Refusal("I cannot describe you to yourself.")
    else:
        find_person_frame(clause, ctx, target)
    ctx.emit("describe", info="description")
    report(clause, ctx, exclude=target)
