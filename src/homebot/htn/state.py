"""``State``: ground atoms indexed by predicate and argument, with an undo trail for backtracking.

A state is a set of ground atoms, each a tuple ``(predicate, arg1, arg2, ...)``.
The planner changes one state in place and undoes the changes when it backtracks
(as JSHOP2 does), instead of copying the state at every operator (as GTPyhop's
``State.copy`` does with ``deepcopy``); the cost of an operator is then the size
of its effects, not the size of the state.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence
from typing import Any

__all__ = ["Atom", "State", "Term", "is_variable"]

Term = Any  #: a constant (str without a leading ``?``, or a number) or a variable (``?x``)
Atom = tuple[Any, ...]  #: ``(predicate, arg1, ...)``


def is_variable(term: Term) -> bool:
    """Whether ``term`` is a variable: a string starting with ``?``."""
    return isinstance(term, str) and term[:1] == "?"


class State:
    """A set of ground atoms with per-predicate and per-argument indexes.

    ``mark()`` returns a point on the undo trail and ``undo(mark)`` takes every
    change after it back, so the planner backtracks without copying.
    """

    __slots__ = ("_by_argument", "_by_predicate", "_trail")

    def __init__(self, atoms: Iterable[Atom] = ()) -> None:
        self._by_predicate: dict[tuple[Any, int], dict[Atom, None]] = {}
        self._by_argument: dict[tuple[tuple[Any, int], int, Any], dict[Atom, None]] = {}
        self._trail: list[tuple[bool, Atom]] = []
        for atom in atoms:
            self._insert(tuple(atom))

    # -- changes --------------------------------------------------------------------------

    def add(self, atom: Atom) -> None:
        """Make ``atom`` true (recorded on the trail)."""
        if self._insert(atom):
            self._trail.append((True, atom))

    def remove(self, atom: Atom) -> None:
        """Make ``atom`` false (recorded on the trail); removing a false atom does nothing."""
        if self._delete(atom):
            self._trail.append((False, atom))

    def mark(self) -> int:
        """A point to come back to with ``undo``."""
        return len(self._trail)

    def undo(self, mark: int) -> None:
        """Take back every change made since ``mark``."""
        trail = self._trail
        while len(trail) > mark:
            added, atom = trail.pop()
            if added:
                self._delete(atom)
            else:
                self._insert(atom)

    def _insert(self, atom: Atom) -> bool:
        predicate = (atom[0], len(atom))
        bucket = self._by_predicate.get(predicate)
        if bucket is None:
            bucket = self._by_predicate[predicate] = {}
        elif atom in bucket:
            return False
        bucket[atom] = None
        index = self._by_argument
        for position in range(1, len(atom)):
            key = (predicate, position, atom[position])
            entries = index.get(key)
            if entries is None:
                index[key] = {atom: None}
            else:
                entries[atom] = None
        return True

    def _delete(self, atom: Atom) -> bool:
        predicate = (atom[0], len(atom))
        bucket = self._by_predicate.get(predicate)
        if bucket is None or atom not in bucket:
            return False
        del bucket[atom]
        for position in range(1, len(atom)):
            del self._by_argument[(predicate, position, atom[position])][atom]
        return True

    # -- queries --------------------------------------------------------------------------

    def __contains__(self, atom: object) -> bool:
        if not isinstance(atom, tuple) or not atom:
            return False
        bucket = self._by_predicate.get((atom[0], len(atom)))
        return bucket is not None and atom in bucket

    def __iter__(self) -> Iterator[Atom]:
        for bucket in self._by_predicate.values():
            yield from bucket

    def __len__(self) -> int:
        return sum(len(bucket) for bucket in self._by_predicate.values())

    def atoms(self, predicate: Any) -> list[Atom]:
        """The atoms of one predicate (any arity), in the order they became true."""
        return [atom for (name, _), bucket in self._by_predicate.items() if name == predicate
                for atom in bucket]

    def candidates(self, predicate: Any, arity: int,
                   bound: Sequence[tuple[int, Any]]) -> Sequence[Atom]:
        """Atoms that may match: the smallest index bucket among the bound positions.

        ``bound`` lists (position, value) pairs, positions counted from 1. The
        result is a snapshot, safe to iterate while the state changes.
        """
        key = (predicate, arity + 1)
        best: dict[Atom, None] | None = self._by_predicate.get(key)
        if best is None:
            return ()
        for position, value in bound:
            entries = self._by_argument.get((key, position, value))
            if entries is None:
                return ()
            if len(entries) < len(best):
                best = entries
        return list(best)

    def copy(self) -> State:
        """An independent state with the same atoms and an empty trail."""
        return State(self)

    def to_sorted_list(self) -> list[Atom]:
        """Every atom, sorted by their text (for printing and tests)."""
        return sorted(self, key=repr)

    def __repr__(self) -> str:
        return f"State({len(self)} atoms)"
