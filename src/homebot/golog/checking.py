"""Static checks of programs against a theory: unknown names and wrong numbers of arguments."""

from __future__ import annotations

import difflib
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
        check_program(theory, procedure.body, f"procedure {procedure.name}")


def check_program(theory: Theory, program: Program, where: str = "the program") -> None:
    """Raise ``GologError`` if the program calls an unknown action or procedure, or a
    fluent or function that is not declared, or any of them with the wrong arity."""
    for call in _calls(program):
        _check_call(theory, call, where)
    for term in _terms(program):
        _check_term(theory, term, where)


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
        case Star(body=body):
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
