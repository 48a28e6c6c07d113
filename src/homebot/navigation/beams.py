"""Monte Carlo localisation's per-beam work as compiled kernels (``homebot.compiled``).

``log_likelihoods`` weighs every particle by one table look-up per beam end
point; ``raycast`` marches rays through the map's solid cells, each stopping
at its first hit. Both are plain Python over scalars and arrays, run compiled
by numba; the float32 arithmetic is the one the vectorised numpy code before
them did (the same cells are looked up). This module is imported when the
filter first weighs a scan.
"""

from __future__ import annotations

import numpy as np

from homebot.compiled import compiled

__all__ = ["log_likelihoods", "raycast"]


@compiled
def log_likelihoods(table: np.ndarray, bx: np.ndarray, by: np.ndarray, px: np.ndarray,
                    py: np.ndarray, c: np.ndarray, s: np.ndarray, rows: int,
                    columns: int) -> np.ndarray:
    """Per particle, the sum of ``table`` at its beams' end cells.

    Beam end points (``bx``, ``by``, robot frame) and particle positions (``px``,
    ``py``) are in cells (float32); ``c``, ``s`` the particles' heading cosines
    and sines. End points off the table take its edge cell.
    """
    total = np.zeros(len(px))
    last_column = np.float32(columns - 1)
    last_row = np.float32(rows - 1)
    zero = np.float32(0.0)
    for i in range(len(px)):
        ci, si, xi, yi = c[i], s[i], px[i], py[i]
        acc = 0.0
        for j in range(len(bx)):
            ex = ci * bx[j]
            ex -= si * by[j]
            ex += xi
            ey = si * bx[j]
            ey += ci * by[j]
            ey += yi
            ex = min(max(ex, zero), last_column)
            ey = min(max(ey, zero), last_row)
            acc += float(table[int(ey) * columns + int(ex)])
        total[i] = acc
    return total


@compiled
def raycast(solid: np.ndarray, x0: np.float32, y0: np.float32, cos: np.ndarray,
            sin: np.ndarray, cells: np.ndarray, steps: np.ndarray) -> np.ndarray:
    """Per ray, ``steps`` at its first sample (``cells`` along it) in a solid cell; inf if none.

    The ray starts at cell coordinates (``x0``, ``y0``) and runs along (``cos``,
    ``sin``); samples off the map are free.
    """
    rows, columns = solid.shape
    hits = np.full(len(cos), np.inf, dtype=np.float32)
    for ray in range(len(cos)):
        for i in range(len(cells)):
            column = cos[ray] * cells[i]
            column += x0
            row = sin[ray] * cells[i]
            row += y0
            if 0 <= column < columns and 0 <= row < rows and solid[int(row), int(column)]:
                hits[ray] = steps[i]
                break
    return hits
