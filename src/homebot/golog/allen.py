"""Allen's interval algebra: the 13 relations, their composition, and a path-consistency solver.

A relation set (a disjunction of basic relations) is a 13-bit mask. The
composition table is not typed in: it is derived from the relations' endpoint
orderings (each basic relation fixes ``<``, ``=`` or ``>`` between the four
endpoint pairs), so ``r3`` is in ``r1 ∘ r2`` exactly when the six endpoints of
three intervals can be ordered on a line with ``A r1 B``, ``B r2 C`` and
``A r3 C`` (the complete sign matrix of the six points is a total preorder,
i.e. transitive). The tests check the table against brute-force
enumeration of integer intervals.

``Network`` holds named intervals and the relation set between every pair;
``path_consistency`` is Allen's / Mackworth's PC-2 (revise ``R(i,j) ∩= R(i,k)
∘ R(k,j)`` until nothing changes); ``solve`` adds backtracking over basic
relations, which makes it complete (path consistency alone is complete only for
the ORD-Horn fragment). ``conflicting`` names a minimal set of constraints that
cannot hold together.

Section banners: #### relations, #### composition, #### networks, #### conflicts.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cache

import numpy as np

__all__ = [
    "ALL",
    "BASIC",
    "CONVERSE",
    "DISJOINT",
    "NAMES",
    "WITHIN",
    "Constraint",
    "Network",
    "compose",
    "conflicting",
    "converse",
    "endpoints",
    "mask_of",
    "names_of",
    "network_of",
    "relation_of",
]

#### relations

#: the 13 basic relations, each with the endpoint orderings it fixes between A and B:
#: (a-, b-), (a-, b+), (a+, b-), (a+, b+), as -1 (<), 0 (=), 1 (>)
_ENDPOINTS: dict[str, tuple[int, int, int, int]] = {
    "before": (-1, -1, -1, -1),
    "meets": (-1, -1, 0, -1),
    "overlaps": (-1, -1, 1, -1),
    "starts": (0, -1, 1, -1),
    "during": (1, -1, 1, -1),
    "finishes": (1, -1, 1, 0),
    "equals": (0, -1, 1, 0),
    "finished-by": (-1, -1, 1, 0),
    "contains": (-1, -1, 1, 1),
    "started-by": (0, -1, 1, 1),
    "overlapped-by": (1, -1, 1, 1),
    "met-by": (1, 0, 1, 1),
    "after": (1, 1, 1, 1),
}

NAMES: tuple[str, ...] = tuple(_ENDPOINTS)
BASIC: tuple[int, ...] = tuple(1 << index for index in range(len(NAMES)))
ALL: int = (1 << len(NAMES)) - 1
_INDEX = {name: index for index, name in enumerate(NAMES)}
_CONVERSE_NAME = {
    "before": "after", "meets": "met-by", "overlaps": "overlapped-by", "starts": "started-by",
    "during": "contains", "finishes": "finished-by", "equals": "equals",
}
_CONVERSE_NAME.update({value: key for key, value in list(_CONVERSE_NAME.items())})
#: the converse of each basic relation, by index
CONVERSE: tuple[int, ...] = tuple(_INDEX[_CONVERSE_NAME[name]] for name in NAMES)


def mask_of(*names: str) -> int:
    """The relation set of these basic relation names (``KeyError`` for an unknown one)."""
    mask = 0
    for name in names:
        mask |= 1 << _INDEX[name]
    return mask


#: A and B share no moment: before, meets, met-by, after
DISJOINT = mask_of("before", "meets", "met-by", "after")
#: A lies inside B: starts, during, finishes, equals
WITHIN = mask_of("starts", "during", "finishes", "equals")


def names_of(mask: int) -> list[str]:
    """The basic relation names in a relation set, in the table's order."""
    return [name for index, name in enumerate(NAMES) if mask >> index & 1]


def endpoints(name: str) -> tuple[int, int, int, int]:
    """The endpoint orderings a basic relation fixes (see the table above)."""
    return _ENDPOINTS[name]


@cache
def converse(mask: int) -> int:
    """``{r˘ : r ∈ mask}``: B's relation to A when A's to B is ``mask``."""
    result = 0
    for index in range(len(NAMES)):
        if mask >> index & 1:
            result |= 1 << CONVERSE[index]
    return result


def relation_of(a: tuple[float, float], b: tuple[float, float]) -> str:
    """The basic relation between two proper intervals ``(start, end)``, start < end."""
    if not (a[0] < a[1] and b[0] < b[1]):
        raise ValueError(f"{a} or {b} is not a proper interval (start before end)")

    def sign(x: float, y: float) -> int:
        return (x > y) - (x < y)

    key = (sign(a[0], b[0]), sign(a[0], b[1]), sign(a[1], b[0]), sign(a[1], b[1]))
    for name, orderings in _ENDPOINTS.items():
        if orderings == key:
            return name
    raise AssertionError("unreachable: every ordering of two proper intervals is a relation")


#### composition

def _sign_matrices() -> np.ndarray:
    """For every (r1, r2, r3): the 6×6 signs between the endpoints a-, a+, b-, b+, c-, c+."""
    count = len(NAMES)
    signs = np.zeros((count, count, count, 6, 6), dtype=np.int8)
    for start, end in ((0, 1), (2, 3), (4, 5)):  # every interval starts before it ends
        signs[..., start, end] = -1
    pairs = ((0, 2), (0, 3), (1, 2), (1, 3))
    for index, name in enumerate(NAMES):
        for (p, q), sign in zip(pairs, _ENDPOINTS[name], strict=True):
            signs[index, :, :, p, q] = sign  # A r1 B
            signs[:, index, :, p + 2, q + 2] = sign  # B r2 C
            signs[:, :, index, p, q + 2] = sign  # A r3 C
    upper = np.triu(np.ones((6, 6), dtype=bool), 1)
    signs = np.where(upper, signs, -np.swapaxes(signs, -1, -2))
    return signs.reshape(count ** 3, 6, 6)


def _transitive(signs: np.ndarray) -> np.ndarray:
    """Which complete sign matrices are total preorders (so the points fit on a line).

    For all p, q, r: ``p = q`` gives ``sign(p, r) = sign(q, r)``, ``q = r`` gives
    ``sign(p, r) = sign(p, q)``, and ``p < q < r`` (or ``>``) gives the same for p, r.
    """
    pq = signs[:, :, :, None]
    qr = signs[:, None, :, :]
    pr = signs[:, :, None, :]
    implied = np.where(pq == 0, qr, np.where(qr == 0, pq, np.where(pq == qr, pq, 2)))
    broken = (implied != 2) & (implied != pr)
    result: np.ndarray = ~broken.any(axis=(1, 2, 3))
    return result


@cache
def _basic_table() -> tuple[tuple[int, ...], ...]:
    """``table[i][j]``: the composition of basic relations i and j, derived from endpoints."""
    count = len(NAMES)
    fits = _transitive(_sign_matrices()).reshape(count, count, count)
    return tuple(tuple(sum(1 << k for k in range(count) if fits[i, j, k]) for j in range(count))
                 for i in range(count))


@cache
def compose(first: int, second: int) -> int:
    """``first ∘ second``: A's possible relations to C given A first B and B second C."""
    table = _basic_table()
    result = 0
    for i in range(len(NAMES)):
        if first >> i & 1:
            row = table[i]
            for j in range(len(NAMES)):
                if second >> j & 1:
                    result |= row[j]
                    if result == ALL:
                        return ALL
    return result


#### networks

@dataclass(frozen=True, slots=True)
class Constraint:
    """``subject relations object`` as given by a person, with where it was written."""

    subject: str
    relations: int
    object: str
    text: str = ""
    place: str = ""

    def __str__(self) -> str:
        shown = self.text or f"{self.subject} {'|'.join(names_of(self.relations))} {self.object}"
        return f"{shown} ({self.place})" if self.place else shown


class Network:
    """Named intervals with the relation set between every ordered pair (ALL when unknown)."""

    def __init__(self, variables: Sequence[str] = ()) -> None:
        self.variables: list[str] = []
        self._index: dict[str, int] = {}
        self.relations: list[list[int]] = []
        for name in variables:
            self.add(name)

    def add(self, name: str) -> int:
        """Add an interval (if new); its index."""
        if name in self._index:
            return self._index[name]
        index = len(self.variables)
        self.variables.append(name)
        self._index[name] = index
        for row in self.relations:
            row.append(ALL)
        self.relations.append([ALL] * (index + 1))
        self.relations[index][index] = mask_of("equals")
        return index

    def copy(self) -> Network:
        other = Network()
        other.variables = list(self.variables)
        other._index = dict(self._index)
        other.relations = [list(row) for row in self.relations]
        return other

    def __contains__(self, name: object) -> bool:
        return name in self._index

    def restrict(self, subject: str, relations: int, object: str) -> bool:
        """Intersect ``subject``–``object`` with ``relations`` (adding both); False if empty."""
        i, j = self.add(subject), self.add(object)
        self.relations[i][j] &= relations
        self.relations[j][i] &= converse(relations)
        return self.relations[i][j] != 0

    def relation(self, subject: str, object: str) -> int:
        """The relation set between two intervals (ALL for an interval not in the network)."""
        if subject not in self._index or object not in self._index:
            return ALL
        return self.relations[self._index[subject]][self._index[object]]

    def path_consistency(self, changed: Iterable[tuple[int, int]] | None = None) -> bool:
        """PC-2: narrow every relation by composition through a third interval.

        ``changed`` lists the pairs to start from (all pairs by default). Returns
        False when some relation becomes empty: the network is inconsistent.
        """
        size = len(self.variables)
        relations = self.relations
        queue = deque(changed if changed is not None else [
            (i, j) for i in range(size) for j in range(i + 1, size)])
        queued = set(queue)
        while queue:
            i, j = queue.popleft()
            queued.discard((i, j))
            rij = relations[i][j]
            if rij == ALL:
                continue
            row_i, row_j, rji = relations[i], relations[j], converse(rij)
            for k in range(size):
                if k in (i, j):
                    continue
                # R(i,k) ∩= R(i,j) ∘ R(j,k); then R(j,k) ∩= R(j,i) ∘ R(i,k), the converse
                # of R(k,j) ∩= R(k,i) ∘ R(i,j). An unknown relation (ALL) narrows nothing.
                rjk = row_j[k]
                if rjk != ALL:
                    old = row_i[k]
                    new = old & compose(rij, rjk)
                    if new != old:
                        if not new:
                            return False
                        row_i[k] = new
                        relations[k][i] = converse(new)
                        pair = (i, k) if i < k else (k, i)
                        if pair not in queued:
                            queued.add(pair)
                            queue.append(pair)
                rik = row_i[k]
                if rik != ALL:
                    old = row_j[k]
                    new = old & compose(rji, rik)
                    if new != old:
                        if not new:
                            return False
                        row_j[k] = new
                        relations[k][j] = converse(new)
                        pair = (j, k) if j < k else (k, j)
                        if pair not in queued:
                            queued.add(pair)
                            queue.append(pair)
        return True

    def solve(self) -> Network | None:
        """A consistent refinement to basic relations everywhere, or None if none exists."""
        network = self.copy()
        if not network.path_consistency():
            return None
        return network._search()

    def _search(self) -> Network | None:
        size = len(self.variables)
        open_pairs = [(bin(self.relations[i][j]).count("1"), i, j)
                      for i in range(size) for j in range(i + 1, size)
                      if self.relations[i][j] & (self.relations[i][j] - 1)]
        if not open_pairs:
            return self
        _, i, j = min(open_pairs)
        for index in range(len(NAMES)):
            if self.relations[i][j] >> index & 1:
                trial = self.copy()
                trial.relations[i][j] = 1 << index
                trial.relations[j][i] = 1 << CONVERSE[index]
                if trial.path_consistency([(i, j)]):
                    found = trial._search()
                    if found is not None:
                        return found
        return None

    def consistent(self) -> bool:
        """Whether the intervals can be placed on a line as the relations say."""
        return self.solve() is not None


def network_of(constraints: Iterable[Constraint],
               variables: Sequence[str] = ()) -> Network | None:
    """A network holding the constraints; None when two of them are directly contradictory."""
    network = Network(variables)
    for constraint in constraints:
        if not network.restrict(constraint.subject, constraint.relations, constraint.object):
            return None
    return network


#### conflicts

def conflicting(constraints: Sequence[Constraint],
                background: Sequence[Constraint] = ()) -> list[Constraint]:
    """A minimal subset of ``constraints`` inconsistent together with ``background``.

    Empty when all of them can hold together. Deletion filter: drop each
    constraint in turn and keep it out if the rest is still inconsistent.
    """
    def consistent(chosen: Sequence[Constraint]) -> bool:
        network = network_of([*background, *chosen])
        return network is not None and network.consistent()

    if consistent(constraints):
        return []
    kept = list(constraints)
    for constraint in list(kept):
        trial = [other for other in kept if other is not constraint]
        if not consistent(trial):
            kept = trial
    return kept
