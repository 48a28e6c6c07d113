"""Clauses: a tagged command cut into one action each, with its arguments as items."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from homebot.language import lexicon
from homebot.language.vocabulary import Token

__all__ = ["Clause", "Item", "build_clauses"]

_ATTRIBUTE_KINDS = frozenset({"posture", "gesture", "clothes"})
_CONTENT_KINDS = frozenset({"entity", "person", "me", "pronoun", "generic", "topic", "info",
                            "property", "count", "quote"})
_QUESTION_KINDS = {"count": "count", "property": "describe", "topic": "tell_me",
                   "info": "tell_me"}


@dataclass(slots=True)
class Item:
    """One argument of a clause: what it is, its value and the preposition before it.

    ``kind`` is room, placement, object, category, door, person, me, pronoun,
    generic, topic, info, property, count, quote, ambiguous or unknown. ``owner``
    is the index of the item this one locates ("Maria *in the kitchen*").
    """

    kind: str
    value: Any
    text: str
    prep: str | None = None
    definite: bool = False
    owner: int | None = None
    position: int = 0
    quantity: int | str | None = None  # "two drinks": 2; "all the fruits": "all"


@dataclass(slots=True)
class Clause:
    """One action with its items, in the order they were said."""

    action: str | None
    verb: str
    items: list[Item] = field(default_factory=list)
    words: list[str] = field(default_factory=list)
    after: bool = False  # said after "after": happens before the clause it follows
    before: bool = False  # said after "before": happens after the clause that follows it
    ignored: list[str] = field(default_factory=list)  # words no item or step took up
    free_text: bool = False  # a handler used the clause's own words (say ..., ask ...)
    preverbal: list[str] = field(default_factory=list)  # unknown words before the verb
    verb_at: int = 0  # how many of ``words`` were said before the verb ("Maria wants ...")

    def first(self, kinds: Iterable[str], preps: Iterable[str | None] | None = None,
              start: int = 0) -> Item | None:
        """The first item of one of ``kinds`` (and, if given, one of ``preps``)."""
        kinds, allowed = set(kinds), None if preps is None else set(preps)
        for item in self.items[start:]:
            if item.kind in kinds and (allowed is None or item.prep in allowed):
                return item
        return None

    def located(self, item: Item) -> Item | None:
        """The place that locates ``item`` ("the apple *on the table*"), if any."""
        index = self.items.index(item)
        for other in self.items:
            if other.owner == index:
                return other
        return None

    def has(self, kind: str) -> bool:
        return any(item.kind == kind for item in self.items)


def build_clauses(tokens: list[Token]) -> list[Clause]:
    """Cut at separators and verbs; verbless pieces join their neighbour."""
    pieces: list[list[Token]] = [[]]
    message = False  # inside "tell Tom that ...": verbs are the message's, not commands
    for index, token in enumerate(tokens):
        if token.kind == "sep":
            pieces.append([])
            message = False
        elif message:
            pieces[-1].append(token)
        elif _opens_message(token, pieces[-1]):
            pieces[-1].append(token)
            message = True
        elif _starts_clause(tokens, index, pieces[-1]):
            pieces.append([token])
        else:
            pieces[-1].append(token)
    pieces = [piece for piece in pieces if piece]
    merged: list[list[Token]] = []
    pending: list[Token] = []
    for piece in pieces:
        if _is_statement(piece):
            merged.append(piece)  # "she's in the office": said of someone in another clause
        elif _has_action_or_question(piece) or _starts_with_unknown_verb(piece):
            merged.append(pending + piece)
            pending = []
        elif merged and _has_object(piece) and _has_object(merged[-1]):
            merged.append(_gapped(merged[-1]) + piece)  # "get me a lemon and some biscuits"
        elif merged:
            merged[-1].extend(piece)
        else:
            pending.extend(piece)
    if pending:
        merged.append(pending)
    clauses = _reorder([_clause(piece) for piece in merged])
    index = 0
    while index < len(clauses) - 1:  # "before you come back, grab the crisps"
        if clauses[index].before and not clauses[index + 1].before:
            clauses[index], clauses[index + 1] = clauses[index + 1], clauses[index]
            index += 1
        index += 1
    clauses = _apply_statements(clauses)
    return [clause for index, clause in enumerate(clauses)
            if not (clause.action == "go" and not clause.items and index + 1 < len(clauses))
            and not _asks_before_question(clauses, index)]


_SUBJECTS = frozenset({"person", "pronoun", "object", "category"})
_PERSON_PRONOUNS = frozenset({"she", "he", "her", "him"})


def _statement(clause: Clause) -> tuple[Item, Item] | None:
    """"Tom is in the study", "she's in the office", "there's a cup on the table",
    "whoever is in the study": a verbless clause saying where someone or something is."""
    if clause.action is not None or len(clause.items) != 2:
        return None
    subject, place = clause.items
    if subject.kind not in _SUBJECTS or place.kind not in {"room", "placement", "ambiguous"}:
        return None
    if place.owner != 0 or clause.ignored or clause.preverbal:
        return None
    return subject, place


def _apply_statements(clauses: list[Clause]) -> list[Clause]:
    """Fold statements of where someone or something is into the clauses they are about:
    the place becomes the locator of that person or thing (or replaces the pronoun that
    refers to them), and the statement itself is dropped."""
    kept: list[Clause] = []
    for index, clause in enumerate(clauses):
        stated = _statement(clause)
        if stated is None or len(clauses) == 1:
            kept.append(clause)
            continue
        subject, place = stated
        others = clauses[index + 1:] + clauses[:index][::-1]
        if not any(_locate(other, subject, place) for other in others):
            kept.append(clause)
    return kept


def _locate(clause: Clause, subject: Item, place: Item) -> bool:
    """Give ``subject``'s place to the matching item of ``clause``; whether one matched."""
    person = subject.kind == "person" or (subject.kind == "pronoun"
                                          and subject.text in _PERSON_PRONOUNS)
    for at, item in enumerate(clause.items):
        located = clause.located(item)
        if located is not None and (located.prep == "from" or item.kind == "person"):
            continue  # already said where it is ("put it in the pantry" is where it goes)
        same = (item.kind == subject.kind and item.value == subject.value
                and subject.kind != "pronoun")
        refers = item.kind == "pronoun" and subject.kind != "pronoun" and (
            (item.text in _PERSON_PRONOUNS or item.text in {"them", "they"}) == person
            or item.text in {"them", "they"})
        backward = subject.kind == "pronoun" and (
            item.kind == "person" if person else item.kind in {"object", "category"})
        if not (same or refers or backward):
            continue
        if refers:
            clause.items[at] = Item(subject.kind, subject.value, subject.text, item.prep,
                                    subject.definite, item.owner, item.position)
        prep = "in" if person or item.kind == "person" else "from"
        _insert_after(clause, at, Item(place.kind, place.value, place.text, prep,
                                       place.definite, at, item.position))
        return True
    return False


def _insert_after(clause: Clause, at: int, new: Item) -> None:
    for item in clause.items:
        if item.owner is not None and item.owner > at:
            item.owner += 1
    clause.items.insert(at + 1, new)


_QUESTIONS = frozenset({"contents", "where", "count", "describe", "describe_person"})


def _asks_before_question(clauses: list[Clause], index: int) -> bool:
    """"tell me what's inside", "check what's on the table": the first clause only
    introduces the question that follows."""
    clause = clauses[index]
    return (clause.action in {"tell", "tell_me", "search"} and index + 1 < len(clauses)
            and clauses[index + 1].action in _QUESTIONS
            and all(item.kind == "me" for item in clause.items))


def _reorder(clauses: list[Clause]) -> list[Clause]:
    """"put the spoon on the table after taking it from the dishwasher": the clause
    after "after" happens first, and its "it" is the object of the main clause."""
    ordered: list[Clause] = []
    for clause in clauses:
        if not (clause.after and ordered):
            ordered.append(clause)
            continue
        main = ordered.pop()
        thing = next((item for item in main.items
                      if item.kind in {"object", "category", "generic"}), None)
        for index, item in enumerate(clause.items):
            if item.kind == "pronoun" and thing is not None:
                clause.items[index] = Item(thing.kind, thing.value, thing.text, item.prep,
                                           thing.definite, item.owner, item.position)
        if thing is not None:
            main.items[main.items.index(thing)] = Item("pronoun", "it", "it", thing.prep)
        ordered.extend([clause, main])
    return ordered


def _starts_clause(tokens: list[Token], index: int, current: list[Token]) -> bool:
    """A verb after a clause that has its own verb, or "after" before a verb."""
    token = tokens[index]
    if token.kind == "word" and token.value in {"after", "before"}:
        return index + 1 < len(tokens) and tokens[index + 1].kind == "action"
    return token.kind == "action" and _has_action_or_question(current)


_WH_WORDS = frozenset({"what", "where", "which", "who", "how", "whether", "if", "when",
                       "why", "whose"})


def _opens_message(token: Token, piece: list[Token]) -> bool:
    """"tell Tom *that* ...", "ask Lisa *what* she would like": what follows is the
    message or the question, whose verbs are not commands."""
    actions = {t.value for t in piece if t.kind == "action"}
    if "tell" in actions and token.kind == "word" and token.value == "that":
        return True
    first = str(token.text).split()[0] if token.kind in {"word", "action"} else ""
    return "ask" in actions and first in _WH_WORDS


def _starts_with_unknown_verb(piece: list[Token]) -> bool:
    """"... and wash it", "then blorp the fridge": a piece that opens with a word the
    robot does not know (or a verb it cannot do) is a clause of its own, not a
    continuation of the one before, so that it is refused or asked about, never dropped."""
    first = piece[0]
    return first.kind == "word" and first.value.isalpha() and (
        first.value in lexicon.IMPOSSIBLE_ACTIONS or first.value in lexicon.NEGATIONS
        or first.value not in lexicon.FUNCTION_WORDS)


_STATEMENT_WORDS = frozenset({"is", "are", "was", "currently", "right", "a", "an", "the",
                              "some", "there", "now", "still"})


def _is_statement(piece: list[Token]) -> bool:
    """[someone or something] is [in / on / at] [a room or piece of furniture]."""
    core = [token for token in piece
            if not (token.kind == "word" and token.value in _STATEMENT_WORDS)]
    if len(core) != 3 or len(core) == len(piece):
        return False
    subject, prep, place = core
    subject_ok = subject.kind in {"person", "pronoun"} or (
        subject.kind == "entity" and len(subject.value) == 1
        and subject.value[0].kind in {"object", "category", "person"})
    place_ok = place.kind == "entity" and all(
        entity.kind in {"room", "placement"} for entity in place.value)
    return subject_ok and prep.kind == "prep" and prep.value in {"in", "on", "at"} and place_ok


def _has_object(piece: list[Token]) -> bool:
    return any(token.kind == "entity" and len(token.value) == 1
               and token.value[0].kind in {"object", "category"} for token in piece)


def _gapped(previous: list[Token]) -> list[Token]:
    """The verb (and a "me" right after it) of the previous clause, for a verbless one."""
    verb_at = next((i for i, token in enumerate(previous) if token.kind == "action"), None)
    if verb_at is None:
        return []
    head = [previous[verb_at]]
    if verb_at + 1 < len(previous) and previous[verb_at + 1].kind == "me":
        head.append(previous[verb_at + 1])
    return head


def _has_action_or_question(piece: list[Token]) -> bool:
    return any(token.kind == "action" or token.kind in _QUESTION_KINDS for token in piece)


def _clause(piece: list[Token]) -> Clause:
    after = bool(piece) and piece[0].kind == "word" and piece[0].value == "after"
    piece_before = bool(piece) and piece[0].kind == "word" and piece[0].value == "before"
    if piece and piece[0].kind == "word" and piece[0].value in {"after", "before"}:
        piece = piece[1:]
    action_token = next((token for token in piece if token.kind == "action"), None)
    if action_token is None:
        question = next((t for t in piece if t.kind in _QUESTION_KINDS), None)
        action = _QUESTION_KINDS[question.kind] if question else None
        clause = Clause(action=action, verb="")
    else:
        clause = Clause(action=action_token.value, verb=action_token.text)
    clause.after = after
    clause.before = bool(piece_before)
    prep: str | None = None
    definite = False
    quantity: int | str | None = None
    unknown: list[str] = []
    unknown_at = 0
    seen_action = action_token is None
    for at, token in enumerate(piece):
        if token is action_token:
            seen_action = True
            clause.verb_at = len(clause.words)
            continue
        if not seen_action and token.kind == "action":
            continue
        clause.words.append(token.text)
        if token.kind == "word":
            if token.value in lexicon.NEGATIONS:
                clause.preverbal.append(token.value)  # "not the lemonade": never dropped
            elif not seen_action and token.value not in lexicon.FUNCTION_WORDS and (
                    token.value.isalpha()):
                clause.preverbal.append(token.value)  # "record what she says"
            if token.value in lexicon.ARTICLES:
                definite = token.value in {"the", "this", "that"}
            elif token.value not in lexicon.FUNCTION_WORDS and token.value.isalpha():
                if not unknown:
                    unknown_at = len(clause.words) - 1
                unknown.append(token.value)
            continue
        if unknown and token.kind not in _CONTENT_KINDS:
            clause.items.append(Item("unknown", " ".join(unknown), " ".join(unknown), prep,
                                     definite, position=unknown_at))
            prep, definite = None, False
        elif unknown:
            clause.ignored.extend(unknown)  # "a blue cup": "blue" is not taken up
        unknown = []
        if token.kind == "quantity":
            quantity, definite = token.value, False
        elif token.kind == "prep":
            prep = token.value
        elif token.kind == "wearing" and not _clothes_follow(piece, at):
            clause.items.append(Item("info", "clothes", token.text, prep, False,
                                     position=len(clause.words) - 1))
        elif token.kind in _ATTRIBUTE_KINDS:
            _attach_attribute(clause, token)
        elif token.kind in _CONTENT_KINDS:
            item = _item(token, prep, definite)
            item.position = len(clause.words) - 1
            item.quantity, quantity = quantity, None
            clause.items.append(item)
            prep, definite = None, False
    if unknown:
        clause.items.append(Item("unknown", " ".join(unknown), " ".join(unknown), prep, definite,
                                 position=unknown_at))
    _link_locations(clause)
    return clause


def _clothes_follow(piece: list[Token], at: int) -> bool:
    for token in piece[at + 1:]:
        if token.kind == "word" and token.value in lexicon.ARTICLES:
            continue
        return token.kind == "clothes"
    return False


def _item(token: Token, prep: str | None, definite: bool) -> Item:
    if token.kind == "entity":
        candidates = token.value
        if len(candidates) == 1:
            return Item(candidates[0].kind, candidates[0].name, token.text, prep, definite)
        return Item("ambiguous", tuple(candidates), token.text, prep, definite)
    return Item(token.kind, token.value, token.text, prep, definite)


def _attach_attribute(clause: Clause, token: Token) -> None:
    """Give a free-standing posture, gesture or clothes to the last described person."""
    for item in reversed(clause.items):
        if item.kind == "person" and "name" not in item.value:
            item.value.setdefault(token.kind, token.value)
            return


def _link_locations(clause: Clause) -> None:
    """Mark each room or placement that follows a thing or person as locating it."""
    for index, item in enumerate(clause.items):
        if index == 0 or item.kind not in {"room", "placement", "ambiguous"}:
            continue
        if item.prep not in {"in", "at", "on", "from"}:
            continue
        previous = clause.items[index - 1]
        if previous.kind in {"person", "object", "category", "generic", "pronoun", "me"}:
            item.owner = index - 1
        elif previous.kind in {"room", "placement", "ambiguous"} and previous.owner is not None:
            item.owner = previous.owner  # "the table in the kitchen" narrows the same thing
