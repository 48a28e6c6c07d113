"""The textual syntax and the Python embedding build the same programs; bad text is pointed at."""

from __future__ import annotations

import pytest

import homebot.golog
import homebot.golog.domains
from homebot.errors import GologError, HomebotError
from homebot.golog import parse_procedures, parse_program
from homebot.golog.build import (
    add,
    and_,
    choice,
    conc,
    const,
    do,
    eq,
    exists,
    f,
    fail,
    ge,
    gt,
    if_,
    lt,
    ne,
    nil,
    not_,
    pi,
    pick_best,
    pproj,
    prob,
    proc,
    procedure,
    search,
    seq,
    solve,
    star,
    wait_for,
    while_,
    with_ctrl,
    with_pol,
)
from homebot.golog.build import test as guard
from homebot.golog.checking import check_theory
from homebot.golog.library import shipped_procedures, shipped_program_names

SORT_CUPS = """
proc sort_cups(P1, P2, P3, H),
  solve(H, reward_cup(P1, P2, P3),
    while not (p1 = pos(P1) and p2 = pos(P2) and p3 = pos(P3)) do
      pickBest(cup, {red, green, blue},
        pickBest(to, {p1, p2, p3, p4},
          move_cup(cup, pos(cup), to)))
    endwhile
  ) %% endsolve
endproc
"""


def test_the_paper_listing_and_the_python_embedding_are_the_same_procedure() -> None:
    built = proc("sort_cups", ["P1", "P2", "P3", "H"], solve(
        "H", f("reward_cup", "P1", "P2", "P3"),
        while_(not_(and_(eq("p1", f("pos", "P1")), eq("p2", f("pos", "P2")),
                         eq("p3", f("pos", "P3")))),
               pick_best("cup", ["red", "green", "blue"],
                         pick_best("to", ["p1", "p2", "p3", "p4"],
                                   do("move_cup", "cup", f("pos", "cup"), "to"))))))
    assert parse_procedures(SORT_CUPS) == [built]


@pytest.mark.parametrize(("text", "built"), [
    ("nil", nil),
    ("fail", fail),
    ("a; b; c", seq("a", "b", "c")),
    ("a, b; c", seq("a", "b", "c")),
    ("a | b | c", choice("a", "b", "c")),
    ("a; b | c", choice(seq("a", "b"), "c")),
    ("(go_right | go_left); stop_here", seq(choice("go_right", "go_left"), "stop_here")),
    ("high || low", conc("high", "low")),
    ("?(x >= 3 & y != z)", guard(and_(ge("x", 3), ne("y", "z")))),
    ("if floor < N then up else down endif", if_(lt(f("floor"), "N"), "up", "down")),
    ("if door_open then enter endif", if_("door_open", "enter")),
    ("star(a; b)", star(seq("a", "b"))),
    ("search(a | b)", search(choice("a", "b"))),
    ("pi(n, floors, ?(lit(n)); serve(n))", pi("n", "floors", seq(guard(f("lit", "n")),
                                                                 do("serve", "n")))),
    ("withPol(watch, work)", with_pol("watch", "work")),
    ("withCtrl battery > 10 do work endwithCtrl", with_ctrl(gt("battery", 10), "work")),
    ("waitFor(start_button = on)", wait_for(eq("start_button", "on"))),
    ("prob(0.7, a, b)", prob(0.7, "a", "b")),
    ('say("I am done.")', do("say", const("I am done."))),
    ("?(exists c in {red, blue}: pos(c) = p4)", guard(exists("c", ["red", "blue"],
                                                           eq(f("pos", "c"), "p4")))),
    ("?(pproj(at_goal, go) > 0.5)", guard(gt(pproj("at_goal", do("go")), 0.5))),
    ("move(x, -1, 2 + 3)", do("move", "x", -1, add(2, 3))),
])
def test_each_construct_reads_as_its_python_form(text: str, built: object) -> None:
    assert parse_program(text) == built


def test_operators_on_formulas_build_the_same_trees() -> None:
    assert (f("a") & f("b") & f("c")) == and_("a", "b", "c")
    assert ~eq("x", 1) == not_(eq("x", 1))
    assert parse_program("?(a & b & c)") == guard(f("a") & "b" & "c")


def test_every_shipped_program_reads_and_prints_back_to_the_same_program() -> None:
    for name in shipped_program_names():
        for shipped in shipped_procedures(name):
            assert parse_program(str(shipped.body)) == shipped.body, shipped.name


@pytest.mark.parametrize(("text", "line", "column", "words"), [
    ("proc p\n  a;\n  b(\nendproc", 4, 1, "expected a term"),
    ("proc p\n  while x do a\nendproc", 3, 1, "endwhile"),
    ("proc p\n  if x a endif\nendproc", 2, 8, "then"),
    ("proc p\n  a $ b\nendproc", 2, 5, "unexpected character"),
    ("a; b\nproc", 1, 1, "expected 'proc'"),
    ("proc p(X,) a endproc", 1, 10, "parameter"),
    ("proc p solve(3, r) endproc", 1, 18, "','"),
    ("proc p a endwhile", 1, 10, "endproc"),
    ("proc p a endproc\nproc p b endproc", 2, 6, "defined twice"),
    ("proc p(X, Y, X) a endproc", 1, 14, "named twice"),
])
def test_malformed_programs_name_the_line_and_column(text: str, line: int, column: int,
                                                     words: str) -> None:
    with pytest.raises(GologError) as raised:
        parse_procedures(text, "bad.golog")
    message = str(raised.value)
    assert message.startswith(f"bad.golog:{line}:{column}:"), message
    assert words in message
    assert isinstance(raised.value, HomebotError)


def test_a_malformed_single_program_is_reported_too() -> None:
    with pytest.raises(GologError, match=r"<program>:1:3: unexpected '\)'"):
        parse_program("a )")


@pytest.mark.parametrize("package", [homebot.golog, homebot.golog.domains])
def test_all_lists_exactly_the_public_names(package: object) -> None:
    import types

    public = {name for name, value in vars(package).items()
              if not name.startswith("_") and not isinstance(value, types.ModuleType)
              and name != "annotations"}
    assert set(package.__all__) == public  # type: ignore[attr-defined]


def test_a_python_function_is_a_procedure() -> None:
    @procedure
    def go_floor(N: object) -> object:
        return while_(ne(f("floor"), N), if_(lt(f("floor"), N), "up", "down"))

    shipped = {p.name: p for p in shipped_procedures("elevator")}
    assert go_floor == shipped["go_floor"]


def test_the_engines_never_load_the_simulator_or_the_interfaces() -> None:
    """Golog and HTN, with their skill executors, reach the world only through skills."""
    import subprocess
    import sys

    engines = ["homebot.golog", "homebot.golog.skill_executor", "homebot.golog.domains",
               "homebot.htn", "homebot.htn.acting"]
    loaded = subprocess.run(
        [sys.executable, "-c", f"import sys\nfor m in {engines!r}: __import__(m)\n"
         "print(' '.join(sorted(m for m in sys.modules if m.startswith(('homebot.sim', "
         "'homebot.cli', 'homebot.scenarios', 'homebot.web')))))"],
        capture_output=True, text=True, check=True).stdout.split()
    assert loaded == []


def test_a_procedure_may_not_take_the_name_of_an_action() -> None:
    theory = homebot.golog.domains.domain_theory("elevator")
    theory.define(*parse_procedures("proc p up endproc\nproc up\n  down\nendproc", "mine.golog"))
    with pytest.raises(GologError, match=r"^mine.golog:2:6: procedure 'up' has the name of an "
                                         r"action"):
        check_theory(theory)


def test_a_number_too_long_to_read_is_an_error_at_its_column() -> None:
    with pytest.raises(GologError, match=r"^<program>:1:13: a number of 5000 digits, too long "
                                         r"to read; write a smaller number"):
        parse_program("build_tower(" + "9" * 5000 + ")")
