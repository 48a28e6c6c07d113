"""Picking trials: seeded table-top scenes, what the head camera makes of them, and a pick
judged by the physics' truth.

``generate_scene`` draws a table in front of the robot with 1-6 catalogue objects;
``perceive`` looks at it with the simulated head camera and the table-top pipeline;
``run_pick`` plans and executes the pick in MuJoCo, and reports the outcome as the robot
sensed it beside the truth (the object off the table, both fingers on it).
``homebot bench manipulation`` runs many and prints their figures.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

__all__ = ["Scene", "SeenObjects", "generate_scene", "perceive", "run_pick"]

_ROBOT_RADIUS, _CLEARANCE = 0.25, 0.12  #: where the robot stands before a table's edge
_LIFTED = 0.05  #: metres off the table for a verified pick


@dataclass(frozen=True)
class Scene:
    """A generated scene: the table, the objects on it, and which one to pick."""

    table: Any  # homebot.sim.arm.SurfaceBox
    objects: list[Any]  # homebot.sim.arm.ObjectBody
    target: str


def generate_scene(rng: np.random.Generator) -> Scene:
    """A table in front of the robot (at the origin, facing +x) with 1-6 catalogue objects."""
    from homebot.sim.arm import ObjectBody, SurfaceBox
    from homebot.world import CATEGORY_DEFAULTS, COLOUR_PALETTE

    height = float(rng.choice([0.7, 0.75, 0.8, 0.9]))
    depth, width = float(rng.uniform(0.5, 0.8)), float(rng.uniform(0.8, 1.6))
    edge = _ROBOT_RADIUS + _CLEARANCE
    table = SurfaceBox("table", (edge + depth / 2, float(rng.uniform(-0.2, 0.2))),
                       (depth, width), height)
    categories = sorted(CATEGORY_DEFAULTS)
    objects: list[ObjectBody] = []
    for index in range(int(rng.integers(1, 7))):
        kind = CATEGORY_DEFAULTS[categories[int(rng.integers(len(categories)))]]
        scale = float(rng.uniform(0.85, 1.15))
        dims = [d * scale for d in kind.dimensions]
        shape = kind.shape.value
        extent = (dims[0], dims[1], dims[2]) if shape == "box" else \
            (dims[0], dims[0], dims[1]) if shape == "cylinder" else (dims[0],) * 3
        radius = math.hypot(extent[0], extent[1]) / 2
        low_y = max(table.center[1] - width / 2, -0.45) + radius
        high_y = min(table.center[1] + width / 2, 0.45) - radius
        for _ in range(40):
            xy = (float(rng.uniform(edge + radius + 0.03, edge + min(depth, 0.6) - radius)),
                  float(rng.uniform(low_y, high_y)))
            if all(math.dist(xy, o.position) > radius + math.hypot(*o.extents[:2]) / 2 + 0.03
                   for o in objects):
                break
        else:
            continue
        rgb = COLOUR_PALETTE[kind.colours[int(rng.integers(len(kind.colours)))]]
        objects.append(ObjectBody(f"object {index}", shape,  # type: ignore[arg-type]
                                  extent, kind.mass * scale ** 3,
                                  {"box": 0.8, "cylinder": 0.7, "sphere": 0.6}[shape],
                                  (rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, 1.0), xy, height,
                                  float(rng.uniform(-math.pi, math.pi))))
    target = objects[int(rng.integers(len(objects)))].name
    return Scene(table, objects, target)


_PANS = (-0.35, 0.0, 0.35)  #: radians: the head's views across the table
_SAME_CLUSTER = 0.08  #: metres from where the robot was told the target stands
_FUSE = 0.012  #: metres: two views' clusters this close are one object (objects stand 3 cm apart)
_PERCEPTION_STREAM = 1802


@dataclass(frozen=True)
class SeenObjects:
    """What the head camera's table-top pipeline made of a scene: the target's cluster (None:
    no cluster near where the target was said to be) and the other clusters, each as the
    grasp planner's ``ObjectGeometry`` from its points (principal axes, extents, height)."""

    target: Any  # ObjectGeometry | None
    others: list[Any]  # ObjectGeometry
    unseen: list[str]  #: objects no cluster stands for (occluded, out of view, merged)


def perceive(scene: Scene, rng: np.random.Generator) -> SeenObjects:
    """Look at ``scene`` with the head camera in three views (``homebot.sim.camera``) and
    segment each (``homebot.perception.tabletop``): the clusters of points above the table.
    The views overlap, and the robot stands still between them: clusters from different
    views whose points come within ``_FUSE`` of each other are one object seen twice
    (perhaps cut by a picture's edge in one), and their points are joined.

    The robot is told which object to pick by where it stands (as a detection would say,
    to within a few centimetres): the target is the largest cluster within 8 cm of that
    point. Which
    objects no cluster stands for is counted from the truth, for the figures only.
    """
    from homebot.manipulation.grasps import ObjectGeometry
    from homebot.perception.tabletop import Segment, segment_tabletop
    from homebot.robot import HeadState
    from homebot.sim.camera import CAMERA_HEIGHT, CameraSimulator, SceneGeometry, Solid
    from homebot.world import Shape

    table = scene.table
    (cx, cy), (depth, width) = table.center, table.size
    geometry = SceneGeometry(np.zeros((0, 4)), np.array(
        [[cx - depth / 2, cy - width / 2, cx + depth / 2, cy + width / 2, table.height]]))
    camera = CameraSimulator(geometry, rng)
    solids = [Solid(Shape(o.shape), o.extents,
                    tuple(int(255 * c) for c in o.rgba[:3]),  # type: ignore[arg-type]
                    o.position[0], o.position[1], o.base, o.yaw) for o in scene.objects]
    tilt = math.atan2(CAMERA_HEIGHT - table.height, cx)
    segments: list[Segment] = []
    for pan in _PANS:
        frame = camera.render(0.0, (0.0, 0.0, 0.0), HeadState(pan, tilt), solids)
        segments += segment_tabletop(frame, rng, expected_height=table.height).segments
    clusters: list[tuple[np.ndarray, tuple[float, float]]] = []
    for group in _fused(segments):
        merged = Segment(np.vstack([segments[k].points for k in group]),
                         np.vstack([segments[k].colours for k in group]),
                         np.concatenate([segments[k].heights for k in group]))
        x, y, _ = merged.position()
        clusters.append((merged.points, (x, y)))
    target = next(o for o in scene.objects if o.name == scene.target)
    near = [k for k, (_, at) in enumerate(clusters)
            if math.dist(at, target.position) < _SAME_CLUSTER]
    chosen = max(near, key=lambda k: len(clusters[k][0])) if near else None
    # Axes and extents from the points; the centre is perception's own estimate (the middle
    # of the top face, or a fitted sphere's centre: the camera sees a ball's near side only).
    geometries = [replace(ObjectGeometry.from_points(
        scene.target if k == chosen else f"cluster {k}", points, table.height),
        center=np.array(at, dtype=float)) for k, (points, at) in enumerate(clusters)]
    unseen = [o.name for o in scene.objects
              if not any(math.dist(at, o.position) < _SAME_CLUSTER for _, at in clusters)]
    return SeenObjects(None if chosen is None else geometries[chosen],
                       [g for k, g in enumerate(geometries) if k != chosen], unseen)


def _fused(segments: list[Any]) -> list[list[int]]:
    """Groups of segments (indices) whose points come within ``_FUSE`` in the plane."""
    from scipy.spatial import cKDTree

    trees = [cKDTree(segment.points[:, :2]) for segment in segments]
    parent = list(range(len(segments)))

    def root(k: int) -> int:
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for a in range(len(segments)):
        for b in range(a + 1, len(segments)):
            if root(a) != root(b) and trees[a].sparse_distance_matrix(
                    trees[b], _FUSE, output_type="ndarray").size:
                parent[root(b)] = root(a)
    groups: dict[int, list[int]] = {}
    for k in range(len(segments)):
        groups.setdefault(root(k), []).append(k)
    return list(groups.values())


def run_pick(scene: Scene, rng: np.random.Generator, payload: float = 1.5, *,
             perceived: bool = False, seed: int = 0) -> dict[str, Any]:
    """Pick ``scene.target``; the outcome as the robot sensed it and as the truth has it.

    ``perceived``: the grasp is planned on the target's point cluster and the other
    objects are the clusters the head camera found (``perceive``, its noise drawn from
    ``seed``); truth stands in only for what perception has nothing for (the target
    without a cluster near it, objects no cluster stands for). Otherwise every object is
    its catalogue shape at its true pose.
    """
    from homebot.manipulation.grasps import ObjectGeometry
    from homebot.manipulation.pick import PickPlan, current_configuration, execute_pick, plan_pick
    from homebot.manipulation.scene import Obstacle, PlanningScene
    from homebot.sim.arm import ArmSimulation
    from homebot.sim.hands import ArmDriver

    wall, cpu = time.perf_counter(), time.process_time()
    sim = ArmSimulation(base=(0.0, 0.0, 0.0), surfaces=[scene.table], objects=scene.objects)
    driver = ArmDriver(sim)
    table = scene.table
    obstacles = [Obstacle("table", "box", (*table.size, table.height),
                          (*table.center, table.height / 2))]
    target = next(o for o in scene.objects if o.name == scene.target)
    truth_for = list(scene.objects)
    geometry = None
    seen_note: dict[str, Any] = {}
    if perceived:
        seen = perceive(scene, np.random.default_rng([seed, _PERCEPTION_STREAM]))
        geometry = seen.target
        truth_for = [o for o in scene.objects if o.name in seen.unseen and o.name != target.name]
        if geometry is None:  # no cluster for the target: its true shape is its obstacle
            truth_for.append(target)
        seen_all = seen.others if geometry is None else [geometry, *seen.others]
        obstacles += [Obstacle(g.name, "box", (*g.extents, g.height),
                               (*g.center, g.base + g.height / 2),
                               math.atan2(float(g.axes[0][1]), float(g.axes[0][0])))
                      for g in seen_all]
        seen_note = {"target_seen": geometry is not None,
                     "others_from_truth": len([o for o in truth_for if o is not target])}
    # The target is among the obstacles too: the approach must not sweep through it (the
    # grasp's own contact with it is allowed by name).
    obstacles += [Obstacle(o.name, o.shape, o.extents, (*o.position, o.base + o.extents[2] / 2),
                           o.yaw) for o in truth_for]
    planning = PlanningScene(sim.model_path, (0.0, 0.0, 0.0), obstacles)
    if geometry is None:  # no cluster for it (or not asked to perceive): its true shape
        geometry = ObjectGeometry.from_shape(target.name, target.shape, target.extents,
                                             target.position, target.yaw, target.base)
    start = sim.time
    plan = plan_pick(planning, geometry, current_configuration(driver), rng, mass=target.mass,
                     payload=payload)
    if isinstance(plan, PickPlan):
        result = execute_pick(driver, plan, mass=target.mass)
        kind = plan.grasp.candidate.kind
    else:
        result, kind = plan, None
    lifted = float(sim.object_position(target.name)[2]) - (target.base + target.extents[2] / 2)
    truth = lifted > _LIFTED and sim.touching_fingers(target.name) == 2
    return {"outcome": result.outcome.value, "held": truth, "grasp": kind,
            "shape": target.shape, "planning": result.planning_seconds,
            "simulated": sim.time - start, "wall": time.perf_counter() - wall,
            "cpu": time.process_time() - cpu, **seen_note}
