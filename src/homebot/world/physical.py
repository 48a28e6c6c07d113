"""Physical sanity of a home: what does not fit where it stands, and by how much.

Pure geometry over shapely shapes, for ``World``'s checks: a footprint reaching past its
room's outline (a fridge half inside a wall, or 100 m wide in a 5 m room), two pieces of
furniture in each other (a table in the counter), a standing person inside furniture.
"""

from __future__ import annotations

from collections.abc import Sequence

from shapely import STRtree
from shapely.geometry import Point, Polygon
from shapely.geometry.base import BaseGeometry

__all__ = ["TOLERANCE", "depth_inside", "length_text", "overlapping_pairs", "points_inside",
           "reach_beyond"]

#: metres of overlap or overreach nobody could see (rounding in a file): not a problem
TOLERANCE = 0.01


def length_text(metres: float) -> str:
    """A length for a message: centimetres under a metre (``"35 cm"``), else metres."""
    if metres < 1.0:
        return f"{metres * 100:.0f} cm"
    return f"{metres:.3g} m"


def reach_beyond(footprint: Polygon, room: Polygon) -> float:
    """How far (metres) the farthest part of ``footprint`` lies outside ``room``; 0 inside.

    The footprint's own corners are measured as well as the part outside: GEOS loses
    that part of a footprint of absurd size (1e308 m), and a corner is where the farthest
    part of a footprint lies beyond a convex room.
    """
    corners = max(room.distance(Point(corner)) for corner in _corners(footprint))
    beyond = footprint.difference(room)
    if beyond.is_empty:
        return corners
    return max(corners, *(room.distance(Point(corner)) for corner in _corners(beyond)))


def overlapping_pairs(footprints: Sequence[Polygon]) -> list[tuple[int, int, float]]:
    """Pairs ``(i, j, depth)``, ``i < j``, of footprints that overlap by more than
    ``TOLERANCE``; ``depth`` is the overlap's narrower side in metres (how far one must move
    to clear the other). An R-tree finds the candidates, so a home of thousands of
    placements is checked in about linear time."""
    if len(footprints) < 2:
        return []
    tree = STRtree(footprints)
    candidates = tree.query(list(footprints), predicate="intersects")
    pairs = []
    for first, second in sorted({(int(a), int(b)) for a, b in candidates.T if a < b}):
        overlap = footprints[first].intersection(footprints[second])
        low_x, low_y, high_x, high_y = overlap.bounds if not overlap.is_empty else (0, 0, 0, 0)
        depth = min(high_x - low_x, high_y - low_y)
        if overlap.area > 0 and depth > TOLERANCE:
            pairs.append((first, second, depth))
    return pairs


def points_inside(footprints: Sequence[Polygon], points: Sequence[tuple[float, float]],
                  ) -> list[tuple[int, int, float]]:
    """Triples ``(point, footprint, depth)``: each point that lies more than ``TOLERANCE``
    inside a footprint, the first such footprint, and how deep (an R-tree again)."""
    if not footprints or not points:
        return []
    tree = STRtree(footprints)
    hits = tree.query([Point(point) for point in points], predicate="intersects")
    inside: dict[int, tuple[int, float]] = {}
    for point, footprint in sorted((int(a), int(b)) for a, b in hits.T):
        depth = depth_inside(footprints[footprint], points[point])
        if depth > TOLERANCE and point not in inside:
            inside[point] = (footprint, depth)
    return [(point, footprint, depth) for point, (footprint, depth) in sorted(inside.items())]


def depth_inside(footprint: Polygon, point: tuple[float, float]) -> float:
    """How far (metres) ``point`` lies inside ``footprint``, from its nearest edge; 0 outside."""
    where = Point(point)
    if not footprint.covers(where):
        return 0.0
    return float(footprint.exterior.distance(where))


def _corners(shape: BaseGeometry) -> list[tuple[float, float]]:
    parts = getattr(shape, "geoms", [shape])
    return [corner for part in parts
            for corner in getattr(part, "exterior", part).coords]
