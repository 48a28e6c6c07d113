"""Looking at a placement with the head camera: views, the table-top pipeline, detections.

The robot, standing at a placement, tilts its head at the surface (whose height
the map gives) and pans across it in as many views as the surface spans; each
frame goes through ``homebot.perception`` (support plane, clusters, recognition)
and every estimate is placed on the map by the robot's own pose estimate. An
estimate off the placement's surface is dropped; two from overlapping views
within a few centimetres are one object. Detections carry the estimated
position, size and mass, so "the biggest" and "the leftmost" come from what was
seen.
"""

from __future__ import annotations

import math

from shapely.geometry import Point

from homebot.geometry import Pose, wrap_angle
from homebot.perception.recognition import ObjectEstimate, TabletopPerception
from homebot.robot import Body, Detection
from homebot.world import World, surface_height

__all__ = ["TableLook"]

_CAMERA_HEIGHT = 1.3  #: metres: the head camera above the floor
#: radians: half the camera's horizontal field of view less a margin, so that neighbouring
#: views overlap by about 0.3 rad: an object cut by one view's edge is whole in the next
_HALF_FIELD = 0.36
_HALF_HEIGHT = 0.25  #: radians: the same for the vertical field of view
_TRUNCATED_REACH = 0.15  #: metres: an estimate cut by the picture's edge this near a whole one

_REACH = 1.0  #: metres from the surface's edge within which the robot sees the surface
_ON_SURFACE = 0.03  #: metres outside the footprint an estimate may lie (its own error)
_SAME_OBJECT = 0.05  #: metres between estimates from two views of one object
_VIEW_SECONDS = 0.7  #: the head turns and the camera settles


class TableLook:
    """Looks at placements for a ``BodyRobot``.

    Args:
        body: the head and camera.
        world: the map: placement footprints, surface heights, approach poses.
        perception: the trained table-top pipeline.
    """

    def __init__(self, body: Body, world: World, perception: TabletopPerception) -> None:
        self.body = body
        self.world = world
        self.perception = perception
        self._sightings = 0  #: detections made so far: each gets its own handle

    def look(self, placement: str, pose: Pose) -> list[Detection]:
        """The objects seen on ``placement`` from ``pose`` (the robot's estimate)."""
        where = self.world.placements.get(placement)
        if where is None or where.footprint.distance(Point(pose.xy())) > _REACH:
            return []
        height = surface_height(where.model)
        seen: list[tuple[ObjectEstimate, tuple[float, float]]] = []
        for pan, tilt in self._views(placement, pose, height):
            self.body.point_head(pan, tilt)
            self.body.tick(max(1, round(_VIEW_SECONDS / self.body.tick_period)))
            for estimate in self.perception.perceive(self.body.camera(), height):
                point = pose.apply(estimate.position[0], estimate.position[1])
                if where.footprint.buffer(_ON_SURFACE).contains(Point(point)):
                    seen.append((estimate, point))
        self.body.point_head(0.0, 0.0)
        return [self._detection(estimate, point, placement, pose)
                for estimate, point in _merged(seen)]

    def _views(self, placement: str, pose: Pose,
               height: float) -> list[tuple[float, float]]:
        """Head angles (pan, tilt) whose frames together cover the placement's surface: its
        near edge and its far edge in one tilt when they fit, else in two."""
        footprint = self.world.placements[placement].footprint
        corners = list(footprint.exterior.coords)[:-1]
        bearings = [wrap_angle(math.atan2(y - pose.y, x - pose.x) - pose.theta) for x, y in corners]
        drop = _CAMERA_HEIGHT - height
        near = max(footprint.exterior.distance(Point(pose.xy())), 0.1)
        far = max(math.dist(pose.xy(), corner) for corner in corners)
        steep, flat = math.atan2(drop, near), math.atan2(drop, far)
        if steep - flat <= 2 * _HALF_HEIGHT:
            tilts = [(steep + flat) / 2]
        else:
            tilts = [steep - _HALF_HEIGHT, flat + _HALF_HEIGHT]
        low, high = min(bearings), max(bearings)
        span = high - low
        if span > math.pi:  # the robot stands over the surface: look ahead only
            return [(0.0, tilt) for tilt in tilts]
        views = max(1, math.ceil((span - 0.2) / (2 * _HALF_FIELD)))
        step = span / views
        return [(low + step * (index + 0.5), tilt) for tilt in tilts for index in range(views)]

    def _detection(self, estimate: ObjectEstimate, point: tuple[float, float],
                   placement: str, pose: Pose) -> Detection:
        self._sightings += 1  # the robot's own handle: this sighting
        return Detection(estimate.label, estimate.category, self._sightings,
                         (round(point[0], 3), round(point[1], 3)),
                         size=round(estimate.size, 3), mass=round(estimate.mass, 3),
                         heading=None if estimate.heading is None else
                         round(wrap_angle(estimate.heading + pose.theta), 4))


def _merged(seen: list[tuple[ObjectEstimate, tuple[float, float]]],
            ) -> list[tuple[ObjectEstimate, tuple[float, float]]]:
    """One estimate per object: of two closer than ``_SAME_OBJECT``, the surer one; an
    estimate cut by the picture's edge only where no whole one lies near it."""
    kept: list[tuple[ObjectEstimate, tuple[float, float]]] = []
    ordered = sorted(seen, key=lambda item: (item[0].truncated, -item[0].confidence))
    for estimate, point in ordered:
        reach = _TRUNCATED_REACH if estimate.truncated else _SAME_OBJECT
        if all(math.dist(point, other) > reach for _, other in kept):
            kept.append((estimate, point))
    return kept


