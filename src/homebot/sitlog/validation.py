"""Load-time checks of a SitLog program: every problem reported with the place it was written."""

from __future__ import annotations

import difflib
from collections.abc import Iterator, Mapping
from types import MappingProxyType

from homebot.errors import DialogueError
from homebot.sitlog.model import (
    BUILTIN_TYPES,
    FINAL,
    RECURSIVE,
    DialogueModel,
    Program,
    Situation,
    functor_of,
)
from homebot.sitlog.terms import Struct, Term, Var, deref, format_term, is_ground

__all__ = ["GROUNDED_TYPES", "OPERATORS", "check_program"]

#: Situation types whose input comes from a perceptual interpreter.
GROUNDED_TYPES = frozenset({"speech", "vision", "people", "skill", "keyboard"})

#: Operators of the functional language: name -> allowed arities.
OPERATORS: Mapping[str, tuple[int, ...]] = MappingProxyType({
    "get": (1, 2), "set": (2,), "inc": (1, 2), "dec": (1, 2), "assign": (2,),
    "apply": (2,), "when": (3,), "say": (1,), "screen": (1,), "history": (1,),
})
_VARIABLE_OPERATORS = frozenset({"get", "set", "inc", "dec"})


def check_program(program: Program) -> None:
    """Raise ``DialogueError`` at the first malformed part of ``program``."""
    types = BUILTIN_TYPES | GROUNDED_TYPES | set(program.options.get("types", ()))
    for model in program.models.values():
        _check_model(program, model, types)


def _check_model(program: Program, model: DialogueModel, types: frozenset[str] | set[str]) -> None:
    if not model.finals():
        raise DialogueError(f"{model.place}: dialogue model {model.name} has no final situation;"
                            " add one with type: final")
    keys = {situation.key for situation in model.situations}
    variables = set(model.locals) | set(program.globals)
    ground: set[str] = set()
    for situation in model.situations:
        if is_ground(situation.id):
            name = format_term(situation.id)
            if name in ground:
                raise DialogueError(f"{situation.place}: situation {name} is defined twice in "
                                    f"dialogue model {model.name}; rename one")
            ground.add(name)
        if situation.type not in types:
            guess = difflib.get_close_matches(situation.type, sorted(types), n=1)
            hint = f"did you mean '{guess[0]}'?" if guess else f"types: {', '.join(sorted(types))}"
            raise DialogueError(f"{situation.place}: unknown situation type "
                                f"'{situation.type}'; {hint}")
        _check_situation(program, model, situation, keys, variables)


def _check_situation(program: Program, model: DialogueModel, situation: Situation,
                     keys: set[tuple[str, int]], variables: set[str]) -> None:
    name = format_term(situation.id)
    if situation.type == FINAL:
        if situation.arcs:
            raise DialogueError(f"{situation.place}: final situation {name} has arcs; a final "
                                "situation ends its model, remove them")
        return
    if not situation.arcs:
        raise DialogueError(f"{situation.place}: situation {name} has no arcs; add at least one "
                            "'Expectation : Action => Next'")
    for term in (*situation.shared_terms(), *situation.prog):
        _check_expression(program, term, variables, situation.place)
    if situation.interpreter is not None and not _known_function(program,
                                                                 situation.interpreter):
        raise DialogueError(f"{situation.place}: interpreter '{situation.interpreter}' is not a "
                            f"user function; functions: {_listed(program.functions)}")
    embedded: DialogueModel | None = None
    if situation.type == RECURSIVE:
        if situation.embedded_dm is None:
            raise DialogueError(f"{situation.place}: recursive situation {name} needs "
                                "embedded_dm")
        embedded = _embedded(program, situation)
    for arc in situation.arcs:
        for term in (arc.expectation, arc.action, arc.next):
            _check_expression(program, term, variables, arc.place)
        target = _constant_key(arc.next)
        if target is not None and target not in keys:
            known = sorted({f"{k[0]}/{k[1]}" if k[1] else k[0] for k in keys})
            guess = difflib.get_close_matches(target[0], [k[0] for k in keys], n=1)
            hint = f"did you mean '{guess[0]}'?" if guess else f"situations: {', '.join(known)}"
            raise DialogueError(f"{arc.place}: unknown next situation "
                                f"'{format_term(arc.next)}' in dialogue model {model.name}; {hint}")
        if embedded is not None:
            expected = _constant_key(arc.expectation)
            finals = {final.key for final in embedded.finals()}
            if expected is not None and expected not in finals:
                listed = ", ".join(sorted(k[0] for k in finals))
                raise DialogueError(f"{arc.place}: '{format_term(arc.expectation)}' is not a final "
                                    f"situation of {embedded.name}; its finals: {listed}")


def _embedded(program: Program, situation: Situation) -> DialogueModel | None:
    key = _constant_key(situation.embedded_dm)
    if key is None or situation.embedded_dm is None:
        return None
    if key not in program.models:
        known = ", ".join(f"{n}/{a}" for n, a in program.models)
        raise DialogueError(f"{situation.place}: embedded_dm "
                            f"'{format_term(situation.embedded_dm)}' is no dialogue model "
                            f"({key[0]}/{key[1]}); models: {known}")
    return program.models[key]


def _constant_key(term: Term | None) -> tuple[str, int] | None:
    """The functor of a constant situation or model name; None for functions and variables."""
    if term is None:
        return None
    term = deref(term)
    if isinstance(term, Struct) and term.functor in OPERATORS:
        return None
    return functor_of(term)


def _check_expression(program: Program, term: Term | None, variables: set[str],
                      place: str) -> None:
    for struct in _structs(term):
        arities = OPERATORS.get(struct.functor)
        if arities is None:
            continue
        if struct.arity not in arities:
            raise DialogueError(f"{place}: bad expression {format_term(struct)}: "
                                f"{struct.functor} takes {' or '.join(map(str, arities))} "
                                "arguments")
        if struct.functor in _VARIABLE_OPERATORS:
            target = deref(struct.args[0])
            if isinstance(target, str) and target not in variables:
                guess = difflib.get_close_matches(target, sorted(variables), n=1)
                hint = f"did you mean '{guess[0]}'?" if guess else "declare it in locals or globals"
                raise DialogueError(f"{place}: bad expression {format_term(struct)}: no variable "
                                    f"'{target}'; {hint}")
        if struct.functor == "apply":
            function, arguments = (deref(a) for a in struct.args)
            key = functor_of(function)
            if key is None and not isinstance(function, Var):
                raise DialogueError(f"{place}: bad expression {format_term(struct)}: apply takes "
                                    "a function such as f(X) and a list of arguments")
            if key is not None and not _known_function(program, key[0]) and (
                    key[0] not in OPERATORS):
                guess = difflib.get_close_matches(key[0], sorted(program.functions), n=1)
                hint = f"did you mean '{guess[0]}'?" if guess else (
                    f"functions: {_listed(program.functions)}")
                raise DialogueError(f"{place}: bad expression {format_term(struct)}: unknown "
                                    f"function '{key[0]}'; {hint}")
            if not isinstance(arguments, tuple | Var):
                raise DialogueError(f"{place}: bad expression {format_term(struct)}: the "
                                    "arguments of apply are a list, e.g. [X, Y]")


def _structs(term: Term | None) -> Iterator[Struct]:
    if term is None:
        return
    term = deref(term)
    if isinstance(term, Struct):
        yield term
        for arg in term.args:
            yield from _structs(arg)
    elif isinstance(term, tuple):
        for item in term:
            yield from _structs(item)


def _known_function(program: Program, name: str) -> bool:
    """Whether ``name`` is a user function; any name may be one of the modules not loaded."""
    return name in program.functions or bool(program.unloaded_functions)


def _listed(functions: Mapping[str, object]) -> str:
    return ", ".join(sorted(functions)) or "none"
