"""Generated programs print to text that reads back as the same program; junk never crashes."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.errors import GologError
from homebot.golog import parse_program
from homebot.golog.expressions import And, Arith, Compare, Const, Exists, Expr, Fn, Not, Or, SetOf
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

NAMES = st.sampled_from(["a", "b", "pos", "loc", "go_up", "move_cup", "x", "P1", "reward"])
NUMBERS = st.one_of(st.integers(-50, 50), st.sampled_from([0.5, 0.25, 1e-7, 2.5e10]))
TERMS = st.recursive(
    st.one_of(NAMES.map(Fn), NUMBERS.map(Const),
              st.sampled_from(["Door B", "I am done."]).map(Const)),
    lambda inner: st.one_of(
        st.builds(Fn, NAMES, st.lists(inner, min_size=1, max_size=3).map(tuple)),
        st.builds(Arith, st.sampled_from(["+", "-", "*", "/"]), inner, inner)),
    max_leaves=6)
FORMULAS: st.SearchStrategy[Expr] = st.recursive(
    st.one_of(st.builds(Compare, st.sampled_from(["=", "!=", "<", "<=", ">", ">="]), TERMS,
                        TERMS),
              NAMES.map(Fn), st.booleans().map(Const)),
    lambda inner: st.one_of(
        inner.map(Not),
        st.lists(inner, min_size=2, max_size=3).map(lambda items: And(tuple(items))),
        st.lists(inner, min_size=2, max_size=3).map(lambda items: Or(tuple(items))),
        st.builds(Exists, NAMES, st.lists(TERMS, min_size=1, max_size=3).map(
            lambda items: SetOf(tuple(items))), inner)),
    max_leaves=5)
DOMAINS = st.one_of(NAMES.map(Fn), st.lists(TERMS, max_size=3).map(
    lambda items: SetOf(tuple(items))))


def _programs(inner: st.SearchStrategy[Program]) -> st.SearchStrategy[Program]:
    many = st.lists(inner, min_size=2, max_size=3).map(tuple)
    return st.one_of(
        many.map(Seq), many.map(Choice), st.builds(Conc, inner, inner),
        st.builds(If, FORMULAS, inner, inner), st.builds(While, FORMULAS, inner),
        inner.map(Star), inner.map(Search), st.builds(Pi, NAMES, DOMAINS, inner),
        st.builds(PickBest, NAMES, DOMAINS, inner), st.builds(WithPol, inner, inner),
        st.builds(WithCtrl, FORMULAS, inner), st.builds(Prob, TERMS, inner, inner),
        st.builds(Solve, TERMS, TERMS, inner))


PROGRAMS = st.recursive(
    st.one_of(st.just(Nil()), NAMES.map(Call),
              st.builds(Call, NAMES, st.lists(TERMS, min_size=1, max_size=3).map(tuple)),
              FORMULAS.map(Guard), FORMULAS.map(WaitFor)),
    _programs, max_leaves=8)


@settings(max_examples=300, deadline=None)
@given(PROGRAMS)
def test_printed_programs_read_back_as_the_same_program(program: Program) -> None:
    assert parse_program(str(program)) == program


TOKENS = st.sampled_from(["a", "b(", ")", ";", ",", "|", "||", "?(", "if", "then", "else",
                          "endif", "while", "do", "endwhile", "solve(", "pi(", "{", "}", "=",
                          "not", "and", "1", "\"s\"", "proc", "endproc", "$", "\n", " "])


@settings(max_examples=300, deadline=None)
@given(st.lists(TOKENS, max_size=25).map(" ".join))
def test_any_text_gives_a_program_or_a_golog_error(text: str) -> None:
    try:
        parse_program(text)
    except GologError as error:
        assert ":" in str(error).splitlines()[0]
