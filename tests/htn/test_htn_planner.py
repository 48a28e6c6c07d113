"""The planner on small domains written with the Python API: refinement, backtracking, bounds."""

from __future__ import annotations

import importlib
import types

import pytest

from homebot.errors import PlanningError
from homebot.htn import Domain, Planner, State, find_cheapest_plan, find_plan, find_plans


def travel_domain() -> Domain:
    """GTPyhop's simple_htn example, the SHOP2 way: walk if near, else take a taxi."""
    domain = Domain("travel")
    domain.declare_axiom(("near", "?a", "?b"), ("", [("distance", "?a", "?b", "?d"),
                                                     ("call", "<=", "?d", 2)]))
    domain.operator(("!walk", "?p", "?from", "?to"), [("at", "?p", "?from")],
                    [("at", "?p", "?from")], [("at", "?p", "?to")], cost=2)
    domain.operator(("!call_taxi", "?p", "?from"), [("at", "?p", "?from")], [],
                    [("taxi-at", "?from")], cost=1)
    domain.operator(("!ride_taxi", "?p", "?from", "?to"),
                    [("at", "?p", "?from"), ("taxi-at", "?from"), ("cash", "?p", "?c"),
                     ("distance", "?from", "?to", "?d"),
                     ("assign", "?fare", ("call", "+", 1.5, ("call", "*", 0.5, "?d"))),
                     ("call", ">=", "?c", "?fare"),
                     ("assign", "?left", ("call", "-", "?c", "?fare"))],
                    [("at", "?p", "?from"), ("taxi-at", "?from"), ("cash", "?p", "?c")],
                    [("at", "?p", "?to"), ("cash", "?p", "?left")], cost="?d")
    domain.method(("travel", "?p", "?to"), ("there", [("at", "?p", "?to")], []))
    domain.method(("travel", "?p", "?to"),
                  ("on-foot", [("at", "?p", "?from"), ("near", "?from", "?to")],
                   [("!walk", "?p", "?from", "?to")]))
    domain.method(("travel", "?p", "?to"),
                  ("by-taxi", [("at", "?p", "?from")],
                   [("!call_taxi", "?p", "?from"), ("!ride_taxi", "?p", "?from", "?to")]))
    return domain


def travel_state(cash: float = 20) -> State:
    return State([("at", "alice", "home"), ("cash", "alice", cash),
                  ("distance", "home", "park", 8), ("distance", "home", "shop", 2)])


def test_first_plan_backtracks_over_methods() -> None:
    domain, state = travel_domain(), travel_state()
    assert find_plan(domain, state, [("travel", "alice", "shop")]).plan.actions() == [
        ("!walk", "alice", "home", "shop")]
    taxi = find_plan(domain, state, [("travel", "alice", "park")]).plan
    assert taxi.actions() == [("!call_taxi", "alice", "home"),
                              ("!ride_taxi", "alice", "home", "park")]
    assert taxi.cost == 9  # call 1 + ride 8 (cost is the distance variable)
    poor = find_plan(domain, travel_state(cash=3), [("travel", "alice", "park")])
    assert not poor and poor.plan is None


def test_state_is_unchanged_by_planning() -> None:
    state = travel_state()
    before = state.to_sorted_list()
    find_plans(travel_domain(), state, [("travel", "alice", "park"), ("travel", "alice", "shop")])
    assert state.to_sorted_list() == before


def test_all_plans_and_the_cheapest() -> None:
    domain, state = travel_domain(), travel_state()
    every = find_plans(domain, state, [("travel", "alice", "shop")])
    assert [len(plan) for plan in every.plans] == [1, 2]
    cheapest = find_cheapest_plan(domain, state, [("travel", "alice", "shop")])
    assert cheapest.plan.cost == 2 and len(cheapest.plans) == 1
    first = find_plans(domain, state, [("travel", "alice", "shop")], limit=1)
    assert first.plans == every.plans[:1]


def test_branches_of_one_method_are_if_then_else() -> None:
    domain = Domain("branches")
    domain.operator(("!a",), add=[("done", "a")])
    domain.operator(("!b",), add=[("done", "b")])
    domain.operator(("!fail",), [("impossible",)])
    domain.method(("task",), ("first", [("flag",)], [("!a",), ("!fail",)]),
                  ("second", [], [("!b",)]))
    domain.method(("task",), ("other-method", [], [("!a",)]))
    plans = find_plans(domain, State([("flag",)]), [("task",)]).plans
    # The first branch holds but fails later: its else-branch is not tried; the next method is.
    assert [plan.actions() for plan in plans] == [[("!a",)]]
    assert plans[0].network[0].how == "other-method"
    assert find_plan(domain, State(), [("task",)]).plan.actions() == [("!b",)]


def test_variables_bound_by_matching_and_first() -> None:
    domain = Domain("hands")
    domain.operator(("!grasp", "?o"), [(":first", ("free", "?h"))],
                    [("free", "?h")], [("holding", "?o", "?h")])
    domain.method(("take", "?a", "?b"), ("", [], [("!grasp", "?a"), ("!grasp", "?b")]))
    state = State([("free", "left"), ("free", "right")])
    every = find_plans(domain, state, [("take", "cup", "plate")])
    assert len(every.plans) == 1
    assert find_plan(domain, state, [("take", "cup", "plate"), ("!grasp", "fork")]).plan is None


def test_forall_or_imply_assign_and_not() -> None:
    domain = Domain("logic")
    domain.operator(("!check",), [("forall", ["?x"], [("item", "?x")], [("ok", "?x")]),
                                  ("or", ("missing",), ("present",)),
                                  ("imply", ("present",), ("assign", "?n", 3)),
                                  ("not", ("item", "c"))], add=[("checked", "?n")])
    state = State([("item", "a"), ("item", "b"), ("ok", "a"), ("ok", "b"), ("present",)])
    assert find_plan(domain, state, [("!check",)]).plan is not None
    state.remove(("ok", "b"))
    assert find_plan(domain, state, [("!check",)]).plan is None


def test_long_plans_need_no_recursion() -> None:
    domain = Domain("long")
    domain.operator(("!step", "?n"), [("at", "?n"), ("next", "?n", "?m")], [("at", "?n")],
                    [("at", "?m")])
    domain.method(("walk",), ("done", [("at", "end")], []),
                  ("more", [("at", "?n")], [("!step", "?n"), ("walk",)]))
    atoms = [("at", 0), *((("next", i, i + 1)) for i in range(2999)), ("next", 2999, "end")]
    result = find_plan(domain, State(atoms), [("walk",)])
    assert len(result.plan) == 3000


def test_bounds_stop_search_cleanly() -> None:
    domain = Domain("loop")
    domain.method(("forever",), ("again", [], [("forever",)]))
    by_depth = Planner(domain, max_depth=50).search(State(), [("forever",)])
    assert not by_depth and by_depth.stopped == "depth"
    by_count = Planner(domain, max_expansions=100).search(State(), [("forever",)])
    assert not by_count and by_count.stopped == "expansions" and by_count.expansions == 101
    ticks = iter(range(1_000_000))
    by_time = Planner(domain, time_limit=10.0, clock=lambda: float(next(ticks))).search(
        State(), [("forever",)])
    assert not by_time and by_time.stopped == "time"


def test_internal_operators_and_errors() -> None:
    domain = Domain("bookkeeping")
    domain.operator(("!!note", "?x"), add=[("noted", "?x")], cost=0)
    domain.operator(("!act", "?x"), [("noted", "?x")])
    domain.method(("do", "?x"), ("", [], [("!!note", "?x"), ("!act", "?x")]))
    plan = find_plan(domain, State(), [("do", "it")]).plan
    assert plan.actions() == [("!!note", "it"), ("!act", "it")] and plan.cost == 1
    assert domain.operators["!!note"].internal
    with pytest.raises(PlanningError, match=r"tasks of domain .bookkeeping.: !!note, !act, do"):
        find_plan(domain, State(), [("dx", "it")])
    with pytest.raises(PlanningError, match="variable"):
        find_plan(domain, State(), [("do", "?x")])
    with pytest.raises(PlanningError, match=r"\(do it too\) has 2 argument\(s\); 'do' is "
                                            r"\(do \?x\)"):
        find_plan(domain, State(), [("do", "it", "too")])
    with pytest.raises(PlanningError, match="twice"):
        domain.operator(("!act", "?y"))
    with pytest.raises(PlanningError, match="must start with '!'"):
        domain.operator(("act", "?y"))
    domain.method(("broken",), ("", [], [("nothing",)]))
    with pytest.raises(PlanningError, match="'nothing' is neither"):
        domain.check()
    unbound = Domain("unbound")
    unbound.operator(("!bad",), add=[("x", "?y")])
    with pytest.raises(PlanningError, match="unbound"):
        find_plan(unbound, State(), [("!bad",)])
    looping = Domain("looping")
    looping.declare_axiom(("p", "?x"), ("", [("p", "?x")]))
    looping.operator(("!a", "?x"), [("p", "?x")])
    with pytest.raises(PlanningError, match="recursed without end"):
        find_plan(looping, State([("foo", 1)]), [("!a", 1)])


def test_state_indexes_and_undo() -> None:
    state = State([("at", "a", 1), ("at", "b", 2), ("at", "c", 1)])
    mark = state.mark()
    state.add(("at", "d", 1))
    state.remove(("at", "a", 1))
    state.remove(("at", "zz", 9))
    assert sorted(state.candidates("at", 2, [(2, 1)])) == [("at", "c", 1), ("at", "d", 1)]
    state.undo(mark)
    assert sorted(state.candidates("at", 2, [(2, 1)])) == [("at", "a", 1), ("at", "c", 1)]
    assert len(state) == 3 and ("at", "b", 2) in state and ("at",) not in state
    assert state.atoms("at") == state.copy().atoms("at")


def test_package_exports_exactly_its_all() -> None:
    package = importlib.import_module("homebot.htn")
    public = {name for name, value in vars(package).items()
              if not name.startswith("_") and not isinstance(value, types.ModuleType)
              and name != "annotations"}
    assert set(package.__all__) == public


def test_an_opt_in_trace_explains_a_failure() -> None:
    domain, state = travel_domain(), travel_state(cash=3)
    quiet = Planner(domain).search(state, [("travel", "alice", "park")])
    traced = Planner(domain, trace=True).search(state, [("travel", "alice", "park")])
    assert quiet.trace is None and quiet.expansions == traced.expansions
    assert traced.trace == [
        "(travel alice park): there does not apply",
        "(travel alice park): on-foot does not apply",
        "(travel alice park): by-taxi",
        "  (!call_taxi alice home): applied",
        "  (!ride_taxi alice home park): precondition does not hold",
    ]
