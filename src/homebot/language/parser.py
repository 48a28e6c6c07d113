"""``parse_command``: a GPSR command to skill steps, a clarification question or a refusal."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from types import MappingProxyType

from homebot.errors import LanguageError
from homebot.language import lexicon
from homebot.language.accounting import account_for
from homebot.language.clauses import Clause, build_clauses
from homebot.language.context import (
    Clarification,
    Context,
    Discourse,
    Refusal,
    describe_item,
    where,
)
from homebot.language.fetching import (
    deliver_pending,
    direct_object,
    handle_bring,
    handle_find_object,
    handle_look,
    handle_open,
    handle_place,
    handle_take,
    handle_want,
    rounds,
)
from homebot.language.normalise import normalise
from homebot.language.people import (
    find_person_frame,
    handle_answer,
    handle_ask,
    handle_follow,
    handle_go,
    handle_greet,
    handle_guide,
    handle_meet,
    handle_return,
    wants_person,
)
from homebot.language.questions import (
    handle_contents,
    handle_describe_person,
    handle_where,
)
from homebot.language.readings import ReadingModel, choose_reading
from homebot.language.reporting import handle_count, handle_tell, handle_tell_me
from homebot.language.result import ParseResult, ParseStatus
from homebot.language.tagging import tag
from homebot.language.vocabulary import Vocabulary, phrase_tokens
from homebot.space.referring import split_spatial
from homebot.task import Step

__all__ = ["MAX_COMMAND_LENGTH", "parse_command"]

MAX_COMMAND_LENGTH = 1000
re_the = re.compile(r"\bthe\s+", re.IGNORECASE)
Handler = Callable[[Clause, Context], None]


def parse_command(text: str, vocabulary: Vocabulary, *,
                  history: Discourse | None = None,
                  readings: ReadingModel | None = None) -> ParseResult:
    """Parse one command. Raises ``LanguageError`` only for input that is not a command
    at all (empty or absurdly long); anything else is a result with a status.

    ``history`` is what earlier commands of a conversation left ("pick up the apple",
    then "put it on the table"): the object and person pronouns refer back to.
    ``readings`` (the robot's beliefs and the cost of a question) lets an ambiguous
    command be carried out on its likeliest reading when that is worth more than asking
    (``homebot.language.readings``); without it every ambiguity is asked about.
    """
    result = _parse(text, vocabulary, history)
    if readings is not None and result.status is ParseStatus.CLARIFY:
        return choose_reading(result, readings,
                              lambda reading: _parse(reading, vocabulary, history))
    return result


def _parse(text: str, vocabulary: Vocabulary, history: Discourse | None) -> ParseResult:
    if not isinstance(text, str) or not text.strip():
        raise LanguageError("the command is empty; say what the robot should do")
    if len(text) > MAX_COMMAND_LENGTH:
        raise LanguageError(f"the command has {len(text)} characters; keep it under "
                            f"{MAX_COMMAND_LENGTH}, one task at a time")
    referred = _spatial_reference(text, vocabulary) if history is None else None
    if referred is not None:
        return referred
    clauses = build_clauses(tag(normalise(text, vocabulary), vocabulary))
    ctx = Context(vocabulary)
    if history is not None:
        ctx.obj, ctx.obj_state = history.obj, history.obj_state
        ctx.person, ctx.last_referent = history.person, history.last_referent
        ctx.delivered = history.obj_state != "held"
        ctx.person_here = False  # found in an earlier command: the robot has moved since
    try:
        if not clauses:
            raise Refusal("I did not hear anything I can do in that command.")
        for clause in clauses:
            handler = _HANDLERS.get(clause.action or "", _no_action)
            for round_ in range(rounds(clause, ctx)):
                if round_:  # each round fetches another one
                    ctx.obj, ctx.obj_state = None, "named"
                handler(clause, ctx)
            account_for(clause, ctx, ctx.steps)
        deliver_pending(ctx)
    except Clarification as clarification:
        return ParseResult(ParseStatus.CLARIFY, text, question=clarification.question,
                           about=clarification.about, options=clarification.options)
    except Refusal as refusal:
        return ParseResult(ParseStatus.REJECT, text, reason=refusal.reason)
    if not ctx.steps:
        return ParseResult(ParseStatus.REJECT, text,
                           reason="I understood no action I can carry out in that command.")
    return ParseResult(ParseStatus.OK, text, steps=list(ctx.steps))


def _spatial_reference(text: str, vocabulary: Vocabulary) -> ParseResult | None:
    """"the left cup", "the cup close to the plate": parse the command without the spatial
    modifiers and record them (``spatial``) on its first ``find_object`` step, where the
    skill resolves them among what it sees (``homebot.space.referring``). None when the
    command has no such modifier or no object search to carry it ("go near the door")."""
    plain, modifiers = split_spatial(text)
    if not modifiers:
        return None
    for modifier in modifiers:  # every word accounted for: a relatum must be known
        relatum = modifier.relatum
        if relatum is not None and vocabulary.index.get(phrase_tokens(relatum)) is None:
            return ParseResult(ParseStatus.CLARIFY, text, question=(
                f"I do not know what '{relatum}' is; which thing do you mean?"))
    result = parse_command(plain, vocabulary)
    if result.status is ParseStatus.CLARIFY:  # "the cup" among several: the modifiers tell
        result = parse_command(_indefinite(plain), vocabulary)
    searches = [index for index, step in enumerate(result.steps) if step.skill == "find_object"]
    if not result or not searches:
        return None
    steps = list(result.steps)
    first = steps[searches[0]]
    steps[searches[0]] = Step("find_object", {**first.args, "spatial": [
        modifier.to_dict() for modifier in modifiers]})
    return ParseResult(ParseStatus.OK, text, steps=steps)


def _indefinite(text: str) -> str:
    """The first "the" made "a": "bring me the cup" asks which cup; "a cup" does not."""
    return re_the.sub("a ", text, count=1)


def _find(clause: Clause, ctx: Context) -> None:
    target = direct_object(clause, skip_me=False)
    if target is not None and target.kind == "me":  # "find me a fruit in the kitchen"
        thing = direct_object(clause)
        target = thing if thing is not None and thing.kind != "me" else target
    if target is None:
        raise Clarification("What or whom should I look for?")
    if wants_person(target, ctx) or (target.kind == "pronoun" and ctx.obj is None):
        find_person_frame(clause, ctx, target)
    elif target.kind in {"room", "placement", "ambiguous"}:
        handle_go(clause, ctx)
    elif target.kind == "unknown":
        raise Refusal(f"I do not know what or who '{target.value}' is in this home.")
    else:
        handle_find_object(clause, ctx, target)


def _take(clause: Clause, ctx: Context) -> None:
    target = direct_object(clause, skip_me=False)
    to_place = clause.first({"room", "placement", "ambiguous"}, {"to"})
    if target is not None and (target.kind == "person" or (
            target.kind == "me" and to_place is not None) or (
            ctx.pronoun_means_person(target) and ctx.obj_state != "held")):
        handle_guide(clause, ctx)
    else:
        handle_take(clause, ctx)


def _bring(clause: Clause, ctx: Context) -> None:
    bare = [item for item in clause.items if item.prep is None and item.kind != "me"]
    to_place = clause.first({"room", "placement", "ambiguous"}, {"to"})
    if bare and to_place is not None and (bare[0].kind == "person" or (
            ctx.pronoun_means_person(bare[0]) and ctx.obj_state != "held")):
        handle_guide(clause, ctx)
    else:
        handle_bring(clause, ctx)


def _go(clause: Clause, ctx: Context) -> None:
    """"move the candle to the desk" carries an object; otherwise the robot goes."""
    target = direct_object(clause, skip_me=False)
    carries = target is not None and (target.kind in {"object", "category", "generic"} or (
        target.kind == "pronoun" and not ctx.pronoun_means_person(target)))
    if carries and clause.first({"room", "placement", "ambiguous", "unknown"}, {"to"}):
        handle_take(clause, ctx)
    elif (target is not None and target.kind == "person" and target.prep is None
          and clause.first({"room", "placement", "ambiguous"}, {"to"})):
        handle_guide(clause, ctx)  # "walk John from the bedroom to the couch"
    else:
        handle_go(clause, ctx)


def _search(clause: Clause, ctx: Context) -> None:
    """search / look around PLACE for THING: go there and look for it."""
    wanted = clause.first({"object", "category", "generic", "person", "pronoun", "me",
                           "unknown"}, {"for"})
    place = next((item for item in clause.items if item.kind in {"room", "placement",
                                                                 "ambiguous", "unknown"}
                  and item.prep in {None, "in", "at", "on", "around"}), None)
    if wanted is None:
        if place is not None and clause.first({"object", "category", "person"}) is None:
            raise Clarification(f"What should I look for at {describe_item(place)}?")
        _find(clause, ctx)
        return
    if wanted.kind == "unknown":
        raise Refusal(f"I do not know what or who '{wanted.value}' is in this home.")
    if wants_person(wanted, ctx):
        find_person_frame(clause, ctx, wanted, place)
        return
    if place is None:
        handle_find_object(clause, ctx, wanted)
        return
    spot = ctx.place_of(place, clause, "look for things")
    ctx.go(spot)
    ctx.found_object(ctx.object_of(wanted), where(spot))


def _no_action(clause: Clause, ctx: Context) -> None:
    first = next(iter(clause.words), "")
    if first in lexicon.IMPOSSIBLE_ACTIONS:
        raise Refusal(f"I cannot {first}: my skills are to go somewhere, find, pick up, place "
                      f"and bring objects, find, greet, follow and guide people, count, "
                      f"describe, answer questions and talk.")
    places = [item for item in clause.items if item.kind in {"room", "placement"}]
    if places:
        raise Clarification(f"What should I do at {describe_item(places[0])}?")
    things = [item for item in clause.items if item.kind in {"object", "category"}]
    if things:
        raise Clarification(f"What should I do with {describe_item(things[0])}?")
    raise Refusal("I did not understand what to do: say an action like bring, go, find, "
                  "follow or tell.")


_HANDLERS: Mapping[str, Handler] = MappingProxyType({
    "go": _go, "return": handle_return, "find": _find, "meet": handle_meet,
    "take": _take, "bring": _bring, "place": handle_place, "count": handle_count,
    "tell": handle_tell, "tell_me": handle_tell_me, "describe": handle_tell_me,
    "answer": handle_answer, "greet": handle_greet, "follow": handle_follow,
    "guide": handle_guide, "ask": handle_ask, "look": handle_look, "open": handle_open,
    "want": handle_want, "contents": handle_contents, "where": handle_where,
    "describe_person": handle_describe_person, "search": _search,
})
