"""Static checks of programs against a theory: unknown names and wrong numbers of arguments."""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Iterator

from homebot.errors import GologError
from homebot.golog.expressions import (
    And,
    Arith,
    Compare,
    Exists,
    Expr,
    Fn,
    Forall,
    Not,
    Or,
    PProj,
    SetOf,
)
from homebot.golog.program import (
    Call,
    Choice,
    Conc,
    If,
    Pi,
    PickBest,
    Prob,
    Program,
    Search,
    Seq,
    Solve,
    Star,
    Test,
    WaitFor,
    While,
    WithCtrl,
    WithPol,
)
from homebot.golog.theory import Theory

__all__ = ["check_program", "check_theory"]


def check_theory(theory: Theory) -> None:
    """Check every procedure of the theory; raise ``GologError`` naming the first problem."""
    for procedure in theory.procedures.values():
        try:
            if procedure.name in theory.actions:
                raise GologError(f"procedure '{procedure.name}' has the name of an action of "
                                 f"the theory '{theory.name}'; rename the procedure")
            check_program(theory, procedure.body, f"procedure {procedure.name}",
                          bound=frozenset(procedure.parameters))
        except GologError as error:  # read from a file: say where the name is written
            named = re.search(r"'(\w+)'", str(error))
            place = procedure.places.get(named.group(1)) if named else None
            if place is None:
                raise
            raise GologError(f"{place}: {error}") from None


def check_program(theory: Theory, program: Program, where: str = "the program", *,
                  bound: frozenset[str] = frozenset()) -> None:
    """Raise ``GologError`` if the program calls an unknown action or procedure, or a
    fluent or function that is not declared, or any of them with the wrong arity, or
    tests a bare name that is neither a fluent, a function nor a bound variable
    (``bound`` holds the names bound around the program, such as parameters)."""
    for call in _calls(program):
        _check_call(theory, call, where)
    for term in _terms(program):
        _check_term(theory, term, where)
    _check_conditions(theory, program, bound, where)


def _check_conditions(theory: Theory, program: Program, bound: frozenset[str],
                      where: str) -> None:
    """A bare name tested as a condition must be a fluent, a function or a variable."""
    if isinstance(program, Pi | PickBest):
        bound = bound | {program.variable}
    programs, expressions = _children(program)
    for expression in expressions:
        _check_truth(theory, expression, bound, where, condition=isinstance(
            program, Test | WaitFor | If | While | WithCtrl))
    for child in programs:
        _check_conditions(theory, child, bound, where)


def _check_truth(theory: Theory, expression: Expr, bound: frozenset[str], where: str, *,
                 condition: bool) -> None:
    match expression:
        case Fn(name=name, args=()) if condition and name not in bound and (
                name not in theory.fluents and name not in theory.functions):
            known = [*theory.fluents, *theory.functions, *bound]
            raise GologError(f"{where}: the condition '{name}' is neither a fluent, a "
                             f"function nor a variable; {_hint(name, known)}")
        case Not(operand=operand):
            _check_truth(theory, operand, bound, where, condition=condition)
        case And(operands=operands) | Or(operands=operands):
            for operand in operands:
                _check_truth(theory, operand, bound, where, condition=condition)
        case Exists(variable=variable, body=body) | Forall(variable=variable, body=body):
            _check_truth(theory, body, bound | {variable}, where, condition=True)
        case PProj(condition=inner, program=program):
            _check_truth(theory, inner, bound, where, condition=True)
            _check_conditions(theory, program, bound, where)
        case Compare(left=left, right=right) | Arith(left=left, right=right):
            _check_truth(theory, left, bound, where, condition=False)
            _check_truth(theory, right, bound, where, condition=False)


def _check_call(theory: Theory, call: Call, where: str) -> None:
    procedure = theory.procedures.get(call.name)
    if procedure is not None:
        expected = len(procedure.parameters)
    elif call.name in theory.actions:
        expected = len(theory.actions[call.name].parameters)
    else:
        known = [*theory.procedures, *theory.actions]
        raise GologError(f"{where}: '{call.name}' is neither an action of the theory "
                         f"'{theory.name}' nor a procedure; {_hint(call.name, known)}")
    if len(call.args) != expected:
        raise GologError(f"{where}: {call} has {len(call.args)} argument(s); "
                         f"'{call.name}' takes {expected}")


def _check_term(theory: Theory, term: Fn, where: str) -> None:
    if not term.args:
        return
    fluent = theory.fluents.get(term.name)
    if fluent is not None:
        if len(term.args) != fluent.arity:
            raise GologError(f"{where}: the fluent {term} has {len(term.args)} argument(s); "
                             f"'{term.name}' takes {fluent.arity}")
        return
    if term.name not in theory.functions:
        known = [*theory.fluents, *theory.functions]
        raise GologError(f"{where}: '{term.name}' is neither a fluent nor a function of the "
                         f"theory '{theory.name}'; {_hint(term.name, known)}")


def _hint(name: str, known: Iterable[str]) -> str:
    names = sorted(set(known))
    guess = difflib.get_close_matches(name, names, n=1)
    return f"did you mean '{guess[0]}'?" if guess else f"known: {', '.join(names) or 'none'}"


def _children(program: Program) -> tuple[list[Program], list[Expr]]:
    match program:
        case Seq(parts=parts):
            return list(parts), []
        case Choice(options=options):
            return list(options), []
        case Test(condition=condition) | WaitFor(condition=condition):
            return [], [condition]
        case If(condition=condition, then=then, otherwise=otherwise):
            return [then, otherwise], [condition]
        case While(condition=condition, body=body) | WithCtrl(condition=condition, body=body):
            return [body], [condition]
        case Star(body=body) | Search(body=body):
            return [body], []
        case Pi(domain=domain, body=body) | PickBest(domain=domain, body=body):
            return [body], [domain]
        case Conc(high=high, low=low):
            return [high, low], []
        case WithPol(policy=policy, program=inner):
            return [policy, inner], []
        case Prob(probability=probability, first=first, second=second):
            return [first, second], [probability]
        case Solve(horizon=horizon, reward=reward, body=body):
            return [body], [horizon, reward]
        case Call(args=args):
            return [], list(args)
    return [], []


def _programs(program: Program) -> Iterator[Program]:
    yield program
    programs, expressions = _children(program)
    for child in programs:
        yield from _programs(child)
    for expression in expressions:
        for inner in _expressions(expression):
            if isinstance(inner, PProj):
                yield from _programs(inner.program)


def _calls(program: Program) -> Iterator[Call]:
    return (node for node in _programs(program) if isinstance(node, Call))


def _terms(program: Program) -> Iterator[Fn]:
    for node in _programs(program):
        for expression in _children(node)[1]:
            yield from (inner for inner in _expressions(expression) if isinstance(inner, Fn))


def _expressions(expression: Expr) -> Iterator[Expr]:
    yield expression
    match expression:
        case Fn(args=args) | SetOf(items=args):
            for arg in args:
                yield from _expressions(arg)
        case Not(operand=operand):
            yield from _expressions(operand)
        case And(operands=operands) | Or(operands=operands):
            for operand in operands:
                yield from _expressions(operand)
        case Compare(left=left, right=right) | Arith(left=left, right=right):
            yield from _expressions(left)
            yield from _expressions(right)
        case Exists(domain=domain, body=body) | Forall(domain=domain, body=body):
            yield from _expressions(domain)
            yield from _expressions(body)
        case PProj(condition=condition):
            yield from _expressions(condition)
