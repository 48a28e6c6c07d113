"""Bluetooth low-energy tags heard by fixed receivers: RSSI by log-distance path loss.

Each tag on an object sends beacons; each receiver reports a received signal
strength (dBm) that falls with the logarithm of the distance (path-loss exponent
``exponent``), shifted by the tag's own transmit power (unknown to the robot) and
scattered by shadowing noise (Gaussian in dB). Deterministic by seed.
"""

from __future__ import annotations

import numpy as np

__all__ = ["rssi_readings"]


def rssi_readings(tag: tuple[float, float], receivers: np.ndarray, rng: np.random.Generator,
                  *, beacons: int = 10, power: float | None = None, exponent: float = 2.2,
                  shadowing: float = 3.0, height: float = 1.0) -> np.ndarray:
    """RSSI readings (beacons, receivers) in dBm of a tag at ``tag`` (map frame) heard by
    ``receivers`` (m, 2); ``power`` is the tag's RSSI at 1 m (drawn from −65…−55 dBm when
    None); ``height`` the receivers' height above the tag, metres."""
    receivers = np.asarray(receivers, dtype=float).reshape(-1, 2)
    if power is None:
        power = float(rng.uniform(-65.0, -55.0))
    flat = np.linalg.norm(receivers - np.asarray(tag, dtype=float)[None, :], axis=1)
    distance = np.sqrt(flat ** 2 + height ** 2)
    mean = power - 10.0 * exponent * np.log10(distance)
    readings: np.ndarray = mean[None, :] + rng.normal(0.0, shadowing, (beacons, len(receivers)))
    return readings
