"""Dialogue models in SitLog's own notation (Listings A1–A4): ``diag_mod/3`` clauses.

A ``.dm`` file holds clauses ``diag_mod(Id, Situations, Local_Vars).``, where each
situation is a list ``[id ==> ..., type ==> ..., arcs ==> [E : A => N, ...]]``, and
optionally ``Global_Vars = [name ==> value, ...].`` (Listing A2), ``functions([...]).``
naming Python modules of user functions, and ``main(Name).``. Errors name the line
and column.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field

from homebot.errors import DialogueError
from homebot.sitlog.model import Arc, DialogueModel, Situation, functor_of
from homebot.sitlog.terms import (
    EMPTY,
    Struct,
    Term,
    Var,
    deref,
    format_term,
    parse_clauses,
    place_in,
)

__all__ = ["DmFile", "read_dm_text"]

_ATTRIBUTES = ("id", "type", "in_arg", "out_arg", "prog", "arcs", "embedded_dm", "input",
               "interpreter", "diag_mod", "recovery", "repeat")


@dataclass
class DmFile:
    """What a ``.dm`` file defines."""

    models: list[DialogueModel] = field(default_factory=list)
    globals: dict[str, Term] = field(default_factory=dict)
    functions: list[str] = field(default_factory=list)
    main: str | None = None


def read_dm_text(text: str, source: str) -> DmFile:
    """Read the clauses of a ``.dm`` text; ``DialogueError`` names line and column."""
    positions: dict[int, int] = {}
    result = DmFile()
    for clause, offset in parse_clauses(text, source, positions):
        reader = _Clause(text, source, positions, offset)
        clause = deref(clause)
        if isinstance(clause, Struct) and clause.functor == "diag_mod" and clause.arity == 3:
            result.models.append(reader.model(clause))
        elif isinstance(clause, Struct) and clause.functor == "=" and isinstance(
                deref(clause.args[0]), Var):
            result.globals.update(reader.pairs(clause.args[1], "global variables"))
        elif isinstance(clause, Struct) and clause.functor == "functions" and clause.arity == 1:
            result.functions.extend(reader.names(clause.args[0]))
        elif isinstance(clause, Struct) and clause.functor == "main" and clause.arity == 1:
            result.main = format_term(clause.args[0])
        else:
            raise reader.error(clause, "expected diag_mod(Id, Situations, Local_Vars), "
                               "Global_Vars = [...], functions([...]) or main(Name)")
    return result


class _Clause:
    def __init__(self, text: str, source: str, positions: dict[int, int], offset: int) -> None:
        self.text = text
        self.source = source
        self.positions = positions
        self.offset = offset

    def place(self, term: Term) -> str:
        offset = self.positions.get(id(term), self.offset)
        return f"{self.source}, {place_in(self.text, offset)}"

    def error(self, term: Term, message: str) -> DialogueError:
        return DialogueError(f"{self.place(term)}: {message}")

    def items(self, term: Term, what: str) -> tuple[Term, ...]:
        value = deref(term)
        if not isinstance(value, tuple):
            raise self.error(term, f"{what} must be a list [...]")
        return value

    def pairs(self, term: Term, what: str) -> dict[str, Term]:
        result = {}
        for item in self.items(term, what):
            pair = deref(item)
            if not (isinstance(pair, Struct) and pair.functor == "==>" and pair.arity == 2
                    and isinstance(deref(pair.args[0]), str)):
                raise self.error(term, f"{what} are written name ==> value, not "
                                 f"{format_term(pair)}")
            result[str(deref(pair.args[0]))] = pair.args[1]
        return result

    def names(self, term: Term) -> list[str]:
        return [format_term(item) if not isinstance(deref(item), str) else str(deref(item))
                for item in self.items(term, "functions")]

    def model(self, clause: Struct) -> DialogueModel:
        head, situations, local_values = clause.args
        if functor_of(head) is None:
            raise self.error(clause, "a dialogue model's id is a name or name(Args)")
        built = tuple(self.situation(item) for item in self.items(situations, "situations"))
        if not built:
            raise self.error(clause, f"dialogue model {format_term(head)} has no situations")
        return DialogueModel(head, built, self.pairs(local_values, "local variables"),
                             self.place(clause))

    def situation(self, term: Term) -> Situation:
        attributes = {("id" if name == "ID" else name): value
                      for name, value in self.pairs(term, "situation attributes").items()}
        for name in attributes:
            if name not in _ATTRIBUTES:
                guess = difflib.get_close_matches(name, _ATTRIBUTES, n=1)
                hint = f"did you mean '{guess[0]}'?" if guess else ", ".join(_ATTRIBUTES)
                raise self.error(term, f"unknown situation attribute '{name}'; {hint}")
        for needed in ("id", "type"):
            if needed not in attributes:
                raise self.error(term, f"a situation needs {needed} ==> ...")
        if functor_of(attributes["id"]) is None:
            raise self.error(term, "a situation's id is a name or name(Args)")
        prog = deref(attributes.get("prog", ()))
        repeat = deref(attributes.get("repeat", 3))
        if not isinstance(repeat, int) or repeat < 1:
            raise self.error(term, "repeat ==> is a whole number of tries, 1 or more")
        interpreter = attributes.get("interpreter")
        return Situation(
            attributes["id"], format_term(attributes["type"]),
            tuple(self.arc(arc) for arc in self.items(attributes.get("arcs", ()), "arcs")),
            attributes.get("in_arg"), attributes.get("out_arg"),
            prog if isinstance(prog, tuple) else (prog,), attributes.get("embedded_dm"),
            attributes.get("input"), format_term(interpreter) if interpreter else None,
            attributes.get("diag_mod"), attributes.get("recovery"), repeat, self.place(term))

    def arc(self, term: Term) -> Arc:
        arc = deref(term)
        if not (isinstance(arc, Struct) and arc.functor == "=>" and arc.arity == 2):
            raise self.error(term, f"an arc is Expectation : Action => Next, not "
                             f"{format_term(arc)}")
        left, following = arc.args
        left = deref(left)
        place = self.place(term)
        if isinstance(left, Struct) and left.functor == ":" and left.arity == 2:
            return Arc(left.args[0], left.args[1], following, place)
        return Arc(left, EMPTY, following, place)
