"""Where a Bluetooth-tagged object is, from signal strengths at fixed receivers (Cosero §6.1.7).

The received strength falls with the log of the distance: ``rssi = power − 10 n
log10(d)``. The tag's ``power`` (its strength at 1 m) is not known: it is a
shared unknown of all receivers, solved together with the position by
non-linear least squares (``scipy.optimize.least_squares``, a robust soft-L1
loss against shadowing), with the path-loss exponent ``n`` fixed or solved too
when there are enough receivers. Readings are smoothed over time first: the
median of each receiver's recent readings. The estimate is coarse (a metre or
so): a hint that tells ``find_object`` which placement to look at first
(``placement_hint``).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping

import numpy as np
from scipy.optimize import least_squares

__all__ = ["TagLocaliser", "laterate", "placement_hint"]


def laterate(receivers: np.ndarray, rssi: np.ndarray, *, exponent: float | None = 2.0,
             height: float = 1.0) -> tuple[float, float]:
    """The tag's position (map frame) from one RSSI per receiver (m,) in dBm.

    ``exponent``: the path-loss exponent, or None to solve it too (needs five or more
    receivers); ``height``: the receivers' height above tags, metres."""
    receivers = np.asarray(receivers, dtype=float).reshape(-1, 2)
    rssi = np.asarray(rssi, dtype=float).reshape(-1)
    if len(receivers) != len(rssi) or len(receivers) < 3:
        raise ValueError("lateration needs one reading for each of at least three receivers")
    solve_exponent = exponent is None and len(receivers) >= 5
    # start at the receivers' centre, weighted towards the strongest
    weights = np.exp((rssi - rssi.max()) / 6.0)
    start = (receivers * weights[:, None]).sum(axis=0) / weights.sum()

    def model(params: np.ndarray) -> np.ndarray:
        x, y, power = params[:3]
        n = params[3] if solve_exponent else exponent
        flat = np.hypot(receivers[:, 0] - x, receivers[:, 1] - y)
        distance = np.sqrt(flat ** 2 + height ** 2)
        residual: np.ndarray = power - 10.0 * float(n or 2.0) * np.log10(distance) - rssi
        return residual

    guess = [start[0], start[1], float(rssi.max())]
    low = [receivers[:, 0].min() - 1, receivers[:, 1].min() - 1, -120.0]
    high = [receivers[:, 0].max() + 1, receivers[:, 1].max() + 1, 0.0]
    if solve_exponent:
        guess.append(2.0)
        low.append(1.5)
        high.append(4.0)
    fit = least_squares(model, np.asarray(guess), bounds=(low, high), loss="soft_l1",
                        f_scale=3.0)
    return (float(fit.x[0]), float(fit.x[1]))


class TagLocaliser:
    """Smooths one tag's readings over time and laterates the smoothed strengths.

    Args:
        receivers: the receivers' positions (m, 2), map frame.
        window: how many recent readings per receiver are kept (median).
    """

    def __init__(self, receivers: np.ndarray, window: int = 30, exponent: float = 2.0) -> None:
        self.receivers = np.asarray(receivers, dtype=float).reshape(-1, 2)
        self.exponent = exponent
        self._recent: deque[np.ndarray] = deque(maxlen=window)

    def add(self, readings: np.ndarray) -> None:
        """Readings (k, m) or (m,) in dBm, one column per receiver."""
        for row in np.asarray(readings, dtype=float).reshape(-1, len(self.receivers)):
            self._recent.append(row)

    def estimate(self) -> tuple[float, float] | None:
        """Where the tag is, from the smoothed readings; None before any."""
        if not self._recent:
            return None
        smoothed = np.median(np.vstack(self._recent), axis=0)
        return laterate(self.receivers, smoothed, exponent=self.exponent)


def placement_hint(position: tuple[float, float],
                   placements: Mapping[str, tuple[tuple[float, float], tuple[float, float]]],
                   ) -> list[str]:
    """Placements (name → footprint centre, size) nearest the laterated position first,
    by the distance from the position to the footprint: where to look first."""
    def gap(item: tuple[str, tuple[tuple[float, float], tuple[float, float]]]) -> float:
        (cx, cy), (sx, sy) = item[1]
        dx = max(abs(position[0] - cx) - sx / 2, 0.0)
        dy = max(abs(position[1] - cy) - sy / 2, 0.0)
        return float(np.hypot(dx, dy))

    return [name for name, _ in sorted(placements.items(), key=lambda item: (gap(item), item[0]))]
