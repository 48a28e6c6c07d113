"""Allen's interval algebra: the composition table and the solver against brute-force intervals."""

from __future__ import annotations

import itertools
from functools import cache

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.golog.allen import (
    ALL,
    BASIC,
    NAMES,
    Constraint,
    Network,
    compose,
    conflicting,
    converse,
    mask_of,
    names_of,
    relation_of,
)

#: every proper interval with integer ends in 0..6: seven points hold any three intervals' order
INTERVALS = [(a, b) for a in range(7) for b in range(7) if a < b]

relations = st.sampled_from(NAMES)
intervals = st.sampled_from(INTERVALS)


@cache
def _all_witnesses() -> dict[tuple[str, str], frozenset[str]]:
    """For every (r1, r2): A's relations to C over all integer intervals A r1 B, B r2 C."""
    found: dict[tuple[str, str], set[str]] = {}
    for a, b, c in itertools.product(INTERVALS, repeat=3):
        found.setdefault((relation_of(a, b), relation_of(b, c)), set()).add(relation_of(a, c))
    return {pair: frozenset(names) for pair, names in found.items()}


def _witnesses(first: str, second: str) -> frozenset[str]:
    return _all_witnesses()[first, second]


def test_there_are_13_basic_relations_each_with_its_converse() -> None:
    assert len(NAMES) == 13 and len(set(NAMES)) == 13
    for name in NAMES:
        assert converse(converse(mask_of(name))) == mask_of(name)
    assert names_of(converse(mask_of("during"))) == ["contains"]
    assert names_of(converse(mask_of("equals"))) == ["equals"]


@pytest.mark.parametrize("first", NAMES)
def test_the_composition_table_row_is_what_brute_force_enumeration_finds(first: str) -> None:
    for second in NAMES:
        assert set(names_of(compose(mask_of(first), mask_of(second)))) == \
            _witnesses(first, second), f"{first} ∘ {second}"


@settings(max_examples=300, deadline=None)
@given(intervals, intervals, intervals)
def test_composition_is_sound_for_any_three_intervals(a: tuple[int, int], b: tuple[int, int],
                                                      c: tuple[int, int]) -> None:
    composed = compose(mask_of(relation_of(a, b)), mask_of(relation_of(b, c)))
    assert mask_of(relation_of(a, c)) & composed


@settings(max_examples=200, deadline=None)
@given(relations, relations)
def test_each_composed_relation_has_a_witness_and_each_witness_is_composed(
        first: str, second: str) -> None:
    assert set(names_of(compose(mask_of(first), mask_of(second)))) == _witnesses(first, second)


@settings(max_examples=100, deadline=None)
@given(st.integers(1, ALL), st.integers(1, ALL), relations, relations)
def test_composition_of_sets_is_the_union_over_members(first: int, second: int,
                                                       x: str, y: str) -> None:
    union = 0
    for i, j in itertools.product(range(13), repeat=2):
        if first & BASIC[i] and second & BASIC[j]:
            union |= compose(BASIC[i], BASIC[j])
    assert compose(first, second) == union
    # converse of a composition: (r ∘ s)˘ = s˘ ∘ r˘
    assert converse(compose(mask_of(x), mask_of(y))) == compose(converse(mask_of(y)),
                                                                converse(mask_of(x)))


def _brute_consistent(names: list[str], constraints: dict[tuple[int, int], int]) -> bool:
    """Whether some integer intervals (ends 0..5) satisfy every constraint."""
    small = [(a, b) for a in range(6) for b in range(6) if a < b]
    for chosen in itertools.product(small, repeat=len(names)):
        if all(mask_of(relation_of(chosen[i], chosen[j])) & mask
               for (i, j), mask in constraints.items()):
            return True
    return False


@settings(max_examples=120, deadline=None)
@given(st.dictionaries(st.sampled_from([(0, 1), (0, 2), (1, 2)]),
                       st.integers(1, ALL), min_size=1, max_size=3))
def test_the_solver_agrees_with_brute_force_on_three_intervals(
        constraints: dict[tuple[int, int], int]) -> None:
    names = ["a", "b", "c"]
    network = Network(names)
    for (i, j), mask in constraints.items():
        network.restrict(names[i], mask, names[j])
    solved = network.solve()
    assert (solved is not None) == _brute_consistent(names, constraints)
    if solved is not None:  # a scenario: one basic relation per pair, consistent with the input
        for (i, j), mask in constraints.items():
            relation = solved.relation(names[i], names[j])
            assert relation in BASIC and relation & mask


@settings(max_examples=60, deadline=None)
@given(st.lists(intervals, min_size=4, max_size=5), st.data())
def test_path_consistency_keeps_the_true_relations_of_real_intervals(
        chosen: list[tuple[int, int]], data: st.DataObject) -> None:
    names = [f"i{k}" for k in range(len(chosen))]
    network = Network(names)
    for i, j in itertools.combinations(range(len(chosen)), 2):
        true = mask_of(relation_of(chosen[i], chosen[j]))
        extra = data.draw(st.integers(0, ALL))  # weaken it into a disjunction
        network.restrict(names[i], true | extra, names[j])
    assert network.path_consistency()
    for i, j in itertools.combinations(range(len(chosen)), 2):
        assert network.relation(names[i], names[j]) & mask_of(relation_of(chosen[i], chosen[j]))


def test_a_before_b_and_b_before_a_conflict_and_both_are_named() -> None:
    constraints = [Constraint("a", mask_of("before"), "b", "a before b"),
                   Constraint("a", mask_of("during"), "c", "a during c"),
                   Constraint("b", mask_of("before"), "a", "b before a")]
    assert [c.text for c in conflicting(constraints)] == ["a before b", "b before a"]
    assert conflicting(constraints[:2]) == []


def test_a_conflict_through_a_third_interval_is_found_by_propagation() -> None:
    # a during b, b before c, c during a: no single pair contradicts itself
    constraints = [Constraint("a", mask_of("during"), "b", "1"),
                   Constraint("b", mask_of("before"), "c", "2"),
                   Constraint("c", mask_of("during"), "a", "3"),
                   Constraint("d", mask_of("after"), "a", "4")]
    assert [c.text for c in conflicting(constraints)] == ["1", "2", "3"]


def test_relation_of_needs_proper_intervals() -> None:
    with pytest.raises(ValueError, match="proper interval"):
        relation_of((1, 1), (0, 2))
