"""The compiled walk of a grown forest's trees, one vector through all of them.

Walking a forest with numpy costs a round of array operations per level of depth,
for every face window the aligner moves and every face identified; compiled, a
tree's walk is a few comparisons. Numba comes with the ``embodied`` extra, as
the face pipeline's scikit-learn does; this module is imported only once a
forest walks.
"""

from __future__ import annotations

import numpy as np

from homebot.compiled import compiled

__all__ = ["walk"]


@compiled
def walk(feature: np.ndarray, threshold: np.ndarray, left: np.ndarray, right: np.ndarray,
         vector: np.ndarray) -> np.ndarray:
    """The leaf each tree sends ``vector`` to: at each inner node (``left`` ≥ 0) go left
    when the node's feature of ``vector`` is at most its threshold, else right."""
    trees = feature.shape[0]
    leaves = np.zeros(trees, dtype=np.intp)
    for tree in range(trees):
        node = 0
        while left[tree, node] >= 0:
            if vector[feature[tree, node]] <= threshold[tree, node]:
                node = left[tree, node]
            else:
                node = right[tree, node]
        leaves[tree] = node
    return leaves
