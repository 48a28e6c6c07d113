"""SitLog terms: parsing with columns, printing as SitLog's history does, unification."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from homebot.errors import DialogueError
from homebot.sitlog import Struct, Text, Var, format_term, parse_term
from homebot.sitlog.terms import MAX_TERM_DEPTH, Trail, copy_term, resolve, unify


@pytest.mark.parametrize("source, printed", [
    ("finish:screen('Good Bye') => fs", "(finish:screen('Good Bye'))=>fs"),
    ("[day(X)]", "[day(X)]"),
    ("x:(a:b)", "x:(a:b)"),
    ("apply(when(If,T,F),[In=='monday',a,b])", "apply(when(If,T,F),[In==monday,a,b])"),
    ("'not ok'", "'not ok'"),
    ('say("Hello there")', "say(Hello there)"),
    ("-3", "-3"),
    ("[]", "[]"),
    ("n + 4 * 2", "n+(4*2)"),
])
def test_parse_and_print(source: str, printed: str) -> None:
    assert format_term(parse_term(source)) == printed


def test_errors_name_the_column_and_what_was_expected() -> None:
    with pytest.raises(DialogueError, match=r"here, column 11: expected ',' or '\)'"):
        parse_term("say(a b)", "here", column_offset=4)
    with pytest.raises(DialogueError, match="column 1: unexpected character"):
        parse_term("{a}", "there")


def test_unify_binds_and_undoes() -> None:
    trail = Trail()
    x, y = Var("X"), Var("Y")
    mark = trail.mark()
    assert unify(Struct("f", (x, "b")), Struct("f", ("a", y)), trail)
    assert resolve(Struct("g", (x, y))) == Struct("g", ("a", "b"))
    trail.undo(mark)
    assert resolve(x) is x
    assert not unify(Struct("f", ("a",)), Struct("f", ("b",)), trail)
    assert not unify((1, 2), (1,), trail)
    assert unify(1, 1.0, trail)


def test_copy_keeps_sharing_and_freshens() -> None:
    term = parse_term("f(X, g(X, Y))")
    copied = copy_term(term)
    assert isinstance(copied, Struct)
    first, inner = copied.args
    assert first is inner.args[0] and first is not term.args[0]


_atoms = st.from_regex(r"[a-z][a-z0-9_]{0,5}", fullmatch=True) | st.sampled_from(
    ["not ok", "Good Bye", "it's"])
_leaves = _atoms | st.integers(-50, 50) | st.builds(Text, st.from_regex(r"[A-Za-z ]{1,8}",
                                                                         fullmatch=True))
_terms = st.recursive(_leaves, lambda inner: st.lists(inner, max_size=3).map(tuple) | st.builds(
    Struct, st.from_regex(r"[a-z][a-z]{0,4}", fullmatch=True),
    st.lists(inner, min_size=1, max_size=3).map(tuple)), max_leaves=12)


@given(_terms)
def test_printing_then_parsing_gives_the_term_back(term: object) -> None:
    printed = format_term(term)  # type: ignore[arg-type]
    if isinstance(term, Text) or "Text(" in repr(term):
        return  # texts print bare, as in SitLog's history; they are not re-readable
    assert parse_term(printed) == term


@pytest.mark.parametrize("source", [
    "f(" * 50_000 + "x" + ")" * 50_000,  # once a RecursionError
    "[" * 50_000 + "]" * 50_000,
    "a:" * 50_000 + "a",  # right-associative: the parser recursed
    "a+" * 50_000 + "a",  # left-associative: a loop, but a term 50,000 deep
    "f(" * (MAX_TERM_DEPTH + 1) + "x" + ")" * (MAX_TERM_DEPTH + 1),
])
def test_a_term_nested_too_deep_is_an_error_with_its_column(source: str) -> None:
    with pytest.raises(DialogueError, match=f"arc.yaml, line 7, column \\d+: the term nests "
                                            f"deeper than {MAX_TERM_DEPTH} levels; flatten it"):
        parse_term(source, "arc.yaml, line 7")


def test_a_term_nested_to_the_limit_is_read_printed_and_unified() -> None:
    source = "f(" * (MAX_TERM_DEPTH - 1) + "X" + ")" * (MAX_TERM_DEPTH - 1)
    term = parse_term(source)
    assert format_term(term) == source
    assert unify(term, parse_term(source.replace("X", "done")), Trail())


def test_a_number_too_long_to_read_is_an_error_at_its_column() -> None:
    with pytest.raises(DialogueError, match=r"^here, column 3: a number of 5000 digits, too long "
                                            r"to read; write a smaller number$"):
        parse_term("f(" + "9" * 5000 + ")", "here")
