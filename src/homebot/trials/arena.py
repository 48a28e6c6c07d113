"""What an arena needs of the floor: whether a spot is free for someone to stand on."""

from __future__ import annotations

from homebot.navigation import Navigator

__all__ = ["free_floor"]


def free_floor(navigator: Navigator, point: tuple[float, float], clear: float) -> bool:
    """Whether ``point`` lies in some room of ``navigator``'s map with ``clear`` metres of
    floor round it (off the map's grid: never)."""
    return navigator.clearance_at(*point) >= clear and \
        navigator.world.room_at(*point) is not None
