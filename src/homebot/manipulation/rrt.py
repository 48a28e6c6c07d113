"""Collision-free arm motion: bidirectional RRT (RRT-Connect) in joint space, as CAESAR
plans its arm's paths, with shortcut smoothing."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

__all__ = ["edge_valid", "rrt_connect", "shortcut"]

Valid = Callable[[np.ndarray], bool]

_STEP = 0.35  #: radians: how far a tree grows towards a sample at once
_RESOLUTION = 0.04  #: radians between collision checks along an edge


def edge_valid(valid: Valid, a: np.ndarray, b: np.ndarray,
               resolution: float = _RESOLUTION) -> bool:
    """Whether the straight joint-space segment from ``a`` to ``b`` is free (ends excluded:
    the caller checked them)."""
    steps = math.ceil(float(np.max(np.abs(b - a))) / resolution)
    return all(valid(a + (b - a) * (i / steps)) for i in range(1, steps))


class _Tree:
    def __init__(self, root: np.ndarray) -> None:
        self.nodes = np.zeros((64, len(root)))
        self.nodes[0] = root
        self.parents = [-1]

    def __len__(self) -> int:
        return len(self.parents)

    def nearest(self, q: np.ndarray) -> int:
        count = len(self.parents)
        return int(np.argmin(np.sum((self.nodes[:count] - q) ** 2, axis=1)))

    def add(self, q: np.ndarray, parent: int) -> int:
        count = len(self.parents)
        if count == len(self.nodes):
            self.nodes = np.vstack((self.nodes, np.zeros_like(self.nodes)))
        self.nodes[count] = q
        self.parents.append(parent)
        return count

    def path_to_root(self, index: int) -> list[np.ndarray]:
        path = []
        while index >= 0:
            path.append(self.nodes[index].copy())
            index = self.parents[index]
        return path


def _extend(tree: _Tree, target: np.ndarray, valid: Valid) -> tuple[str, int]:
    """Grow ``tree`` one step towards ``target``: reached, advanced or trapped."""
    near = tree.nearest(target)
    start = tree.nodes[near]
    gap = target - start
    distance = float(np.max(np.abs(gap)))
    reached = distance <= _STEP
    new = target if reached else start + gap * (_STEP / distance)
    if not valid(new) or not edge_valid(valid, start, new):
        return "trapped", near
    return ("reached" if reached else "advanced"), tree.add(new.copy(), near)


def _connect(tree: _Tree, target: np.ndarray, valid: Valid) -> tuple[str, int]:
    status, index = "advanced", -1
    while status == "advanced":
        status, index = _extend(tree, target, valid)
    return status, index


def rrt_connect(start: np.ndarray, goal: np.ndarray, valid: Valid, lower: np.ndarray,
                upper: np.ndarray, rng: np.random.Generator,
                max_iterations: int = 2000) -> list[np.ndarray] | None:
    """A collision-free joint-space path from ``start`` to ``goal`` (both valid), or None.

    Two trees grow from the ends towards random samples in turn, each trying to connect
    to the other's newest node (Kuffner & LaValle's RRT-Connect).
    """
    if edge_valid(valid, start, goal):
        return [start.copy(), goal.copy()]
    trees = (_Tree(start), _Tree(goal))
    for iteration in range(max_iterations):
        grow, other = (trees[0], trees[1]) if iteration % 2 == 0 else (trees[1], trees[0])
        sample = rng.uniform(lower, upper)
        status, new = _extend(grow, sample, valid)
        if status == "trapped":
            continue
        status, met = _connect(other, grow.nodes[new], valid)
        if status == "reached":
            half_a = grow.path_to_root(new)
            half_b = other.path_to_root(met)
            path = half_a[::-1] + half_b[1:]
            return path if grow is trees[0] else path[::-1]
    return None


def shortcut(path: list[np.ndarray], valid: Valid, rng: np.random.Generator,
             attempts: int = 40) -> list[np.ndarray]:
    """Smooth ``path`` by replacing stretches with straight segments where they are free."""
    path = list(path)
    for _ in range(attempts):
        if len(path) <= 2:
            break
        i, j = sorted(int(k) for k in rng.choice(len(path), size=2, replace=False))
        if j - i < 2:
            continue
        if edge_valid(valid, path[i], path[j]):
            path = path[:i + 1] + path[j:]
    return path
