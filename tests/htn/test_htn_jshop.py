"""JSHOP2 / SHOP2 files: domains and problems load, and malformed files give placed errors."""

from __future__ import annotations

import contextlib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.errors import PlanningError
from homebot.htn import State, find_plans, read_domain, read_domain_text, read_problem_text
from homebot.htn.sexpr import MAX_NESTING, read_forms

DOMAIN = """\
; a small JSHOP2 domain: move boxes between rooms with a robot
(defdomain boxes
  ((:operator (!pickup ?b ?r) ((box-at ?b ?r) (robot-at ?r) (hand-empty))
              ((box-at ?b ?r) (hand-empty)) ((holding ?b)))
   (:operator (!drop ?b ?r) ((holding ?b) (robot-at ?r))
              ((holding ?b)) ((box-at ?b ?r) (hand-empty)))
   (:operator (!go ?from ?to) ((robot-at ?from)) ((robot-at ?from)) ((robot-at ?to))
              (call + 1 1))
   (:- (same ?x ?x) nil)
   (:- (elsewhere ?b ?r) ((box-at ?b ?q) (not (same ?q ?r))))
   (:method (move ?b ?to)
            already ((box-at ?b ?to)) nil
            carry ((elsewhere ?b ?to) (box-at ?b ?from))
            (:ordered (goto ?from) (!pickup ?b ?from) (goto ?to) (!drop ?b ?to)))
   (:method (goto ?r)
            here ((robot-at ?r)) ()
            walk ((robot-at ?x)) ((!go ?x ?r)))))
"""

PROBLEM = """\
(defproblem tidy boxes
  ((robot-at hall) (hand-empty) (box-at red kitchen) (box-at blue hall))
  ((move red hall) (move blue hall)))
"""


def test_domain_and_problem_plan() -> None:
    domain = read_domain_text(DOMAIN, "boxes.jshop")
    problem = read_problem_text(PROBLEM, "tidy.jshop")[0]
    assert (problem.name, problem.domain) == ("tidy", "boxes")
    result = find_plans(domain, State(problem.atoms), problem.tasks)
    assert [plan.actions() for plan in result.plans] == [[
        ("!go", "hall", "kitchen"), ("!pickup", "red", "kitchen"), ("!go", "kitchen", "hall"),
        ("!drop", "red", "hall")]]
    assert result.plans[0].cost == 6


def test_shop2_task_markers_are_read_as_plain_tasks() -> None:
    marked = DOMAIN.replace("(:ordered (goto ?from) (!pickup ?b ?from)",
                            "(:ordered (:task goto ?from) (:task !pickup ?b ?from)")
    assert marked != DOMAIN
    problem = read_problem_text(PROBLEM.replace("(move red hall)", "(:task move red hall)"))[0]
    plain_problem = read_problem_text(PROBLEM)[0]
    assert problem.tasks == plain_problem.tasks
    assert find_plans(read_domain_text(marked), State(problem.atoms), problem.tasks).plans == \
        find_plans(read_domain_text(DOMAIN), State(problem.atoms), problem.tasks).plans


def test_reading_from_a_file(tmp_path: Path) -> None:
    path = tmp_path / "boxes.jshop"
    path.write_text(DOMAIN, encoding="utf-8")
    assert read_domain(path).name == "boxes"
    with pytest.raises(PlanningError, match="cannot read"):
        read_domain(tmp_path / "missing.jshop")


@pytest.mark.parametrize(("text", "place", "words"), [
    ("(defdomain d ((:operator (!a) () () ())", "1:1", "never closed"),
    ("(defdomain d ())) ", "1:17", "without a matching"),
    ("(defdomain d (\n  (:operator (!a) () ())))", "2:3", "4 or 5 parts"),
    ("(defdomain d (\n  (:method (t) () ((missing)))))", "2:3", "'missing' is neither"),
    ("(defdomain d ((:operator (!a) ((assign x 1)) () ())))", "1:15", "needs a variable"),
    ("(defdomain d ((:operator (!a) ((call frob 1)) () ())))", "1:15", "unknown function"),
    ("(defdomain d ((:bogus)))", "1:15", "unknown domain item"),
    ("(defdomain d ((:operator (!a) () () ()) 'x))", "1:41", "Lisp quoting"),
    ("(defdomain d ((:operator (a) () () ())))", "1:15", "must start with '!'"),
    ("(defdomain d ((:method (t) name-only)))", "1:15", "needs a precondition"),
    ('(defdomain d ((:operator (!a) () () ("x))))', "1:38", "close the string"),
    ("(defdomain d ((:operator (!a ?x) () () ())\n  (:method (t ?x) () ((!a ?x ?x)))))", "2:3",
     "(!a ?x ?x) has 2 argument(s); '!a' is (!a ?x)"),
])
def test_errors_name_line_and_column(text: str, place: str, words: str) -> None:
    with pytest.raises(PlanningError) as caught:
        read_domain_text(text, "bad.jshop")
    message = str(caught.value)
    assert message.startswith(f"bad.jshop:{place}") or f"bad.jshop:{place}" in message
    assert words in message


def test_reader_keeps_places_and_values() -> None:
    forms = read_forms('(a 1 2.5 "two words")\n  (b)', "x")
    assert [(form.line, form.column) for form in forms] == [(1, 1), (2, 3)]
    assert forms[0].items == ("a", 1, 2.5, "two words")


ALPHABET = st.sampled_from([*"()  ?!:;-\n\"'", "defdomain", "defproblem", ":operator",
                            ":method", ":-", "not", "or", "call", "forall", ":first", "nil",
                            "p", "?x", "1"])


@settings(max_examples=300, deadline=None)
@given(st.lists(ALPHABET, max_size=60))
def test_fuzzed_files_give_errors_never_crashes(tokens: list[str]) -> None:
    text = " ".join(tokens)
    for read in (read_domain_text, read_problem_text):
        with contextlib.suppress(PlanningError):
            read(text, "fuzz.jshop")


@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=0, max_value=len(DOMAIN) - 1),
       st.integers(min_value=1, max_value=40), st.text(max_size=6))
def test_mutated_domain_gives_errors_never_crashes(start: int, length: int, insert: str) -> None:
    text = DOMAIN[:start] + insert + DOMAIN[start + length:]
    try:
        domain = read_domain_text(text, "mutated.jshop")
    except PlanningError:
        return
    problem = read_problem_text(PROBLEM)[0]
    with contextlib.suppress(PlanningError):
        find_plans(domain, State(problem.atoms), problem.tasks, max_expansions=2000)


ERRANDS = """\
; list terms, dotted pairs and a variable add list, as SHOP2 domains use them
(defdomain errands
  ((:operator (!buy ?item) ((sells shop ?item)) () ((bought ?item)))
   (:operator (!!remember ?facts) () () ?facts 0)
   (:method (shop (?item . ?rest)) () ((!buy ?item) (shop ?rest)))
   (:method (shop nil) () ((!!remember ((done shopping) (list (bought-all yes))))))
   (:method (errands) ((wants (?first . ?others))) ((shop (?first . ?others))))))
"""


def test_list_terms_dotted_pairs_and_variable_effects() -> None:
    domain = read_domain_text(ERRANDS, "errands.jshop")
    state = State([("sells", "shop", item) for item in ("milk", "bread", "eggs")])
    state.add(("wants", ("milk", "bread", "eggs")))
    plan = find_plans(domain, state, [("errands",)]).plans[0]
    assert plan.actions()[:3] == [("!buy", "milk"), ("!buy", "bread"), ("!buy", "eggs")]
    assert plan.actions()[3] == ("!!remember", (("done", "shopping"), ("list", ("bought-all",
                                                                                  "yes"))))
    assert plan.cost == 3
    state.remove(("sells", "shop", "eggs"))
    assert not find_plans(domain, state, [("errands",)])
    problem = read_problem_text("(defproblem p errands ((sells shop tea)) ((shop (tea))))")[0]
    assert problem.tasks == (("shop", ("tea",)),)
    assert find_plans(domain, State(problem.atoms), problem.tasks).plans[0].actions() == [
        ("!buy", "tea"), ("!!remember", (("done", "shopping"), ("list", ("bought-all", "yes"))))]


def test_a_variable_effect_must_hold_atoms() -> None:
    domain = read_domain_text("(defdomain d ((:operator (!!note ?x) () () ?x)))")
    with pytest.raises(PlanningError, match="list of atoms"):
        find_plans(domain, State(), [("!!note", "oops")])


@pytest.mark.parametrize("depth", [MAX_NESTING + 1, 100_000])
def test_parentheses_nested_too_deep_are_an_error_with_their_place(depth: int) -> None:
    # 100,000 nested parentheses once ended in a RecursionError
    text = "(defdomain deep (\n  " + "(" * depth + ")" * depth + "))\n"
    with pytest.raises(PlanningError, match=f"deep.jshop:2:{MAX_NESTING + 1}: parentheses nest "
                                            f"deeper than {MAX_NESTING} levels"):
        read_domain_text(text, "deep.jshop")


def test_parentheses_nested_to_the_limit_are_read() -> None:
    forms = read_forms("(" * MAX_NESTING + ")" * MAX_NESTING, "x")
    depth, form = 0, forms[0]
    while form.items:
        depth, form = depth + 1, form.items[0]
    assert depth == MAX_NESTING - 1


def test_a_large_file_of_many_forms_is_read_in_linear_time() -> None:
    # each form's line used to be counted from the start of the text: quadratic
    text = "(a b)\n" * 50_000
    forms = read_forms(text, "many")
    assert len(forms) == 50_000 and (forms[-1].line, forms[-1].column) == (50_000, 1)
