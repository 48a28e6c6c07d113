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

    Order is part of the state, as in JSHOP2: atoms are listed (and matched) in the
    order they became true; an atom made true again goes to the end; ``undo`` puts a
    removed atom back exactly where it was, so planning twice from equal states gives
    the same plan. Each atom carries the number of the insertion that made it true; a
    bucket an undo put out of order is sorted again the next time it is read.

    Protections (JSHOP2's ``:protection``) are counted per atom: an operator may not
    delete a protected atom. They are on the same trail.
    """

    __slots__ = ("_by_argument", "_by_predicate", "_count", "_protected", "_trail",
                 "_unsorted")

    def __init__(self, atoms: Iterable[Atom] = ()) -> None:
        self._by_predicate: dict[tuple[Any, int], dict[Atom, int]] = {}
        self._by_argument: dict[tuple[tuple[Any, int], int, Any], dict[Atom, int]] = {}
        # (kind, atom, number): kind 0 added, 1 removed, 2 protected, 3 unprotected
        self._trail: list[tuple[int, Atom, int]] = []
        self._count = 0
        self._protected: dict[Atom, int] = {}
        self._unsorted: set[Any] = set()
        for atom in atoms:
            self._insert(tuple(atom), self._next())

    def _next(self) -> int:
        self._count += 1
        return self._count

    # -- changes --------------------------------------------------------------------------

    def add(self, atom: Atom) -> None:
        """Make ``atom`` true (recorded on the trail); it goes after every true atom."""
        number = self._count + 1
        if self._insert(atom, number):
            self._count = number
            self._trail.append((0, atom, number))

    def remove(self, atom: Atom) -> None:
        """Make ``atom`` false (recorded on the trail); removing a false atom does nothing."""
        number = self._delete(atom)
        if number:
            self._trail.append((1, atom, number))

    def protect(self, atom: Atom) -> None:
        """Protect ``atom`` once more (JSHOP2's ``(:protection ATOM)`` in an add list)."""
        self._protected[atom] = self._protected.get(atom, 0) + 1
        self._trail.append((2, atom, 0))

    def unprotect(self, atom: Atom) -> None:
        """Take one protection of ``atom`` away (nothing when it has none)."""
        count = self._protected.get(atom, 0)
        if count:
            if count == 1:
                del self._protected[atom]
            else:
                self._protected[atom] = count - 1
            self._trail.append((3, atom, 0))

    def is_protected(self, atom: Atom) -> bool:
        """Whether some operator protects ``atom`` (it may then not be deleted)."""
        return atom in self._protected

    def mark(self) -> int:
        """A point to come back to with ``undo``."""
        return len(self._trail)

    def undo(self, mark: int) -> None:
        """Take back every change made since ``mark``, restoring the order of the atoms."""
        trail = self._trail
        while len(trail) > mark:
            kind, atom, number = trail.pop()
            if kind == 0:
                self._delete(atom)
            elif kind == 1:
                self._insert(atom, number, restore=True)
            elif kind == 2:
                count = self._protected[atom]
                if count == 1:
                    del self._protected[atom]
                else:
                    self._protected[atom] = count - 1
            else:
                self._protected[atom] = self._protected.get(atom, 0) + 1

    def _insert(self, atom: Atom, number: int, restore: bool = False) -> bool:
        predicate = (atom[0], len(atom))
        bucket = self._by_predicate.get(predicate)
        if bucket is None:
            bucket = self._by_predicate[predicate] = {}
        elif atom in bucket:
            return False
        if restore and bucket and next(reversed(bucket.values())) > number:
            self._unsorted.add(predicate)
        bucket[atom] = number
        index = self._by_argument
        for position in range(1, len(atom)):
            key = (predicate, position, atom[position])
            entries = index.get(key)
            if entries is None:
                index[key] = {atom: number}
            else:
                if restore and entries and next(reversed(entries.values())) > number:
                    self._unsorted.add(key)
                entries[atom] = number
        return True

    def _delete(self, atom: Atom) -> int:
        """Remove ``atom``; its insertion number, or 0 when it was not true."""
        predicate = (atom[0], len(atom))
        bucket = self._by_predicate.get(predicate)
        if bucket is None:
            return 0
        number = bucket.pop(atom, 0)
        if number:
            for position in range(1, len(atom)):
                del self._by_argument[(predicate, position, atom[position])][atom]
        return number

    def _sorted(self, key: Any, bucket: dict[Atom, int]) -> dict[Atom, int]:
        """``bucket`` in insertion order again (after an undo put an atom back)."""
        self._unsorted.discard(key)
        ordered = sorted(bucket.items(), key=lambda item: item[1])
        bucket.clear()
        bucket.update(ordered)
        return bucket

    # -- queries --------------------------------------------------------------------------

    def __contains__(self, atom: object) -> bool:
        if not isinstance(atom, tuple) or not atom:
            return False
        bucket = self._by_predicate.get((atom[0], len(atom)))
        return bucket is not None and atom in bucket

    def __iter__(self) -> Iterator[Atom]:
        unsorted = self._unsorted
        for key, bucket in self._by_predicate.items():
            yield from (self._sorted(key, bucket) if unsorted and key in unsorted else bucket)

    def __len__(self) -> int:
        return sum(len(bucket) for bucket in self._by_predicate.values())

    def atoms(self, predicate: Any) -> list[Atom]:
        """The atoms of one predicate (any arity), in the order they became true."""
        unsorted = self._unsorted
        return [atom for key, bucket in self._by_predicate.items() if key[0] == predicate
                for atom in (self._sorted(key, bucket) if unsorted and key in unsorted
                             else bucket)]

    def candidates(self, predicate: Any, arity: int,
                   bound: Sequence[tuple[int, Any]]) -> Sequence[Atom]:
        """Atoms that may match: the smallest index bucket among the bound positions.

        ``bound`` lists (position, value) pairs, positions counted from 1. The
        result is a snapshot in the order the atoms became true, safe to iterate
        while the state changes.
        """
        key = (predicate, arity + 1)
        best: dict[Atom, int] | None = self._by_predicate.get(key)
        if best is None:
            return ()
        best_key: Any = key
        for position, value in bound:
            index_key = (key, position, value)
            entries = self._by_argument.get(index_key)
            if entries is None:
                return ()
            if len(entries) < len(best):
                best, best_key = entries, index_key
        if self._unsorted and best_key in self._unsorted:
            self._sorted(best_key, best)
        return list(best)

    def copy(self) -> State:
        """An independent state with the same atoms (in order), protections and an empty trail."""
        copied = State(self)
        copied._protected = dict(self._protected)
        return copied

    def to_sorted_list(self) -> list[Atom]:
        """Every atom, sorted by their text (for printing and tests)."""
        return sorted(self, key=repr)

    def __repr__(self) -> str:
        return f"State({len(self)} atoms)"
