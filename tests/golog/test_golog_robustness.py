"""Generated programs over the elevator theory either run or raise ``GologError``; never crash."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.errors import GologError
from homebot.golog import Interpreter, SimulatedExecutor
from homebot.golog.domains import elevator_theory
from homebot.golog.expressions import And, Arith, Compare, Const, Expr, Fn, Not, SetOf
from homebot.golog.program import (
    Call,
    Choice,
    Conc,
    If,
    Nil,
    Pi,
    PickBest,
    Prob,
    Program,
    Search,
    Seq,
    Solve,
    Star,
    WaitFor,
    While,
    WithCtrl,
    WithPol,
)
from homebot.golog.program import Test as Guard

NUMBERS = st.integers(-1, 7).map(Const)
TERMS: st.SearchStrategy[Expr] = st.one_of(
    NUMBERS, st.just(Fn("floor")), st.just(Fn("n")), st.just(Const("x")),
    st.builds(lambda t: Fn("lit", (t,)), NUMBERS),
    st.builds(lambda a, b: Arith("+", a, b), NUMBERS, st.just(Fn("floor"))))
FORMULAS: st.SearchStrategy[Expr] = st.one_of(
    st.builds(Compare, st.sampled_from(["=", "<", ">="]), TERMS, TERMS),
    st.just(Fn("alarm")), st.builds(lambda t: Fn("lit", (t,)), TERMS),
    st.booleans().map(Const),
    st.builds(lambda a, b: And((a, Not(b))), st.just(Fn("door_open")), st.just(Fn("alarm"))))
ACTIONS = st.one_of(st.sampled_from(["up", "down", "open", "close", "ring", "reset_alarm",
                                     "park", "nope"]).map(Call),
                    st.builds(lambda t: Call("turnoff", (t,)), TERMS),
                    st.builds(lambda t: Call("go_floor", (t,)), TERMS))


def _programs(inner: st.SearchStrategy[Program]) -> st.SearchStrategy[Program]:
    many = st.lists(inner, min_size=2, max_size=3).map(tuple)
    domain = st.one_of(st.just(Fn("floors")), st.just(SetOf((Const(1), Const(2)))),
                       st.just(Const(3)))
    return st.one_of(
        many.map(Seq), many.map(Choice), st.builds(Conc, inner, inner),
        st.builds(If, FORMULAS, inner, inner), st.builds(While, FORMULAS, inner),
        inner.map(Star), inner.map(Search), st.builds(Pi, st.just("n"), domain, inner),
        st.builds(PickBest, st.just("n"), domain, inner), st.builds(WithPol, inner, inner),
        st.builds(WithCtrl, FORMULAS, inner),
        st.builds(Prob, st.sampled_from([Const(0.3), Const(2), Const("p")]), inner, inner),
        st.builds(Solve, st.sampled_from([Const(2), Const(-1), Const("h")]),
                  st.sampled_from([Fn("floor"), Const(1), Fn("lit")]), inner))


PROGRAMS = st.recursive(st.one_of(st.just(Nil()), ACTIONS, FORMULAS.map(Guard),
                                  FORMULAS.map(WaitFor)), _programs, max_leaves=6)


@settings(max_examples=150, deadline=None)
@given(PROGRAMS, st.integers(0, 3))
def test_generated_programs_run_or_raise_golog_error(program: Program, seed: int) -> None:
    theory = elevator_theory(floors=4, start=2, lit=(3,))
    executor = SimulatedExecutor(theory, seed=seed, patience=1)
    try:
        run = Interpreter(theory, executor, seed=seed, max_steps=80).run(program)
    except GologError:
        return
    assert run.success or run.reason
