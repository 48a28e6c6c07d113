"""Manipulation in physics: grasping generated table-top scenes, bad input, physical HRI.

Every pick is judged by the simulator's truth, never by the robot's own sensing:

- **grasping**: ``--scenes`` seeded scenes, each a table (height, size drawn) in front of
  the robot with 1-6 objects of the catalogue's categories (every shape: box, cylinder,
  sphere; dimensions and mass varied ±15 %). The robot picks one of them, chosen at random:
  grasp selection on the point cluster the head camera's table-top pipeline found for it,
  the other clusters as obstacles (``--objects truth``: the catalogue shapes at their true
  poses instead; truth also stands in for what no cluster stands for), RRT-Connect
  to the pre-grasp, then physics: move in, close, lift, retract. A pick is verified when the
  object is off the table by 5 cm and both fingers touch it after the retract. Planning time
  is CPU time (``time.process_time``) of grasp selection + RRT; run under ``taskset -c 0``
  for one core. Speed is simulated seconds over wall seconds of the whole pick (scene
  building, planning, physics), and over this process's CPU seconds (the same on a core
  nobody else shares).
- **bad input**: an unreachable object, one above the payload, a world file whose
  ``robot.arm`` names a missing or malformed MJCF file: each must give a clear outcome or a
  ``HomebotError``, never a traceback.
- **physical HRI** (handover, guided by the hand, carrying a table, opening and closing a
  door): sections measured by ``homebot.bench.manipulation_hri``.
"""

from __future__ import annotations

import argparse
import importlib
import math
import statistics
import tempfile
import time
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from rich.console import Console
from rich.table import Table

from homebot.bench.arguments import count, seed
from homebot.errors import HomebotError

__all__ = ["Scene", "SeenObjects", "add_arguments", "generate_scene", "perceive", "run",
           "run_pick"]

_ROBOT_RADIUS, _CLEARANCE = 0.25, 0.12  #: where the robot stands before a table's edge
_LIFTED = 0.05  #: metres off the table for a verified pick
#: physical HRI sections: figure functions ``f(seed) -> dict`` of
#: ``homebot.bench.manipulation_hri`` (part B), each reported as "not built" while absent
_HRI_SECTIONS = {"handover": "handover_figures", "guided by the hand": "guided_figures",
                 "carrying a table": "carry_table_figures", "opening a door": "door_figures"}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--scenes", type=count("--scenes", 1, 10_000), default=300,
                        help="generated table-top scenes to pick from")
    parser.add_argument("--seed", type=seed, default=0, help="the first scene's seed")
    parser.add_argument("--only", choices=["all", "grasping", "bad-input", "hri"],
                        default="all", help="run one section only")
    parser.add_argument("--objects", choices=["perceived", "truth"], default="perceived",
                        help="plan grasps on the head camera's point clusters (truth only "
                             "where perception has none), or on the true shapes and poses")


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


def _grasping(scenes: int, first: int, objects: str = "perceived") -> dict[str, Any]:
    runs = []
    for index in range(scenes):
        rng = np.random.default_rng(first + index)
        runs.append(run_pick(generate_scene(rng), rng, perceived=objects == "perceived",
                             seed=first + index))
    held = [r for r in runs if r["held"]]
    sensed_right = sum((r["outcome"] == "held") == r["held"] for r in runs)
    planned = [r["planning"] for r in runs]
    by_shape = {shape: f"{sum(r['held'] for r in runs if r['shape'] == shape)}/"
                       f"{sum(r['shape'] == shape for r in runs)}"
                for shape in ("box", "cylinder", "sphere")}
    outcomes: dict[str, int] = {}
    for r in runs:
        outcomes[r["outcome"]] = outcomes.get(r["outcome"], 0) + 1
    perception: dict[str, Any] = {"objects": objects}
    if objects == "perceived":
        perception["target without a cluster (truth stood in)"] = sum(
            1 for r in runs if not r.get("target_seen", True))
        perception["other objects without a cluster (truth stood in)"] = sum(
            r.get("others_from_truth", 0) for r in runs)
    return {
        "scenes": scenes,
        **perception,
        "verified picks %": round(100.0 * len(held) / scenes, 1),
        "verified by shape": by_shape,
        "outcomes": outcomes,
        "monitor agrees with truth %": round(100.0 * sensed_right / scenes, 1),
        "median planning ms": round(1000 * statistics.median(planned), 1),
        "p95 planning ms": round(1000 * float(np.quantile(planned, 0.95)), 1),
        "speed x real time": round(sum(r["simulated"] for r in runs) /
                                   sum(r["wall"] for r in runs), 1),
        # the same per CPU second of this process: what one core gives when it is not shared
        "speed x real time per CPU second": round(sum(r["simulated"] for r in runs) /
                                                  sum(r["cpu"] for r in runs), 1),
        "targets": {"verified picks %": 90.0, "median planning ms": 1000.0,
                    "speed x real time": 5.0},
    }


def _bad_input() -> dict[str, Any]:
    from homebot.sim.arm import ObjectBody, SurfaceBox

    rng = np.random.default_rng(7)
    table = SurfaceBox("table", (1.4, 0.0), (1.6, 0.8), 0.75)
    far = ObjectBody("far cup", "cylinder", (0.07, 0.07, 0.12), 0.3, position=(2.0, 0.0))
    heavy = ObjectBody("anvil", "box", (0.08, 0.08, 0.1), 6.0, position=(0.75, 0.0))
    near = SurfaceBox("table", (0.65, 0.0), (0.5, 0.8), 0.75)
    figures: dict[str, Any] = {
        "unreachable target": run_pick(Scene(table, [far], far.name), rng)["outcome"],
        "heavier than payload": run_pick(Scene(near, [heavy], heavy.name), rng)["outcome"],
    }
    figures["malformed MJCF in a world file"] = _malformed_mjcf()
    return figures


def _malformed_mjcf() -> str:
    """What the embodied robot says when a world's ``robot.arm`` names a broken MJCF file."""
    from homebot.sim.arm import ArmSimulation

    with tempfile.TemporaryDirectory() as folder:
        broken = Path(folder) / "arm.xml"
        broken.write_text("<mujoco>\n  <worldbody>\n    <body><geom size='x'/></body>\n"
                          "  </worldbody>\n</mujoco>\n", encoding="utf-8")
        try:
            ArmSimulation(base=(0.0, 0.0, 0.0), model_path=broken)
        except HomebotError as error:
            return f"{type(error).__name__}: {str(error).replace(folder, '$TMP')}"
    return "accepted (wrong: the file is malformed)"


def _hri(seed: int) -> dict[str, Any]:
    try:
        module = importlib.import_module("homebot.bench.manipulation_hri")
    except ModuleNotFoundError:
        return {section: "not built" for section in _HRI_SECTIONS}
    figures: dict[str, Any] = {}
    for section, function in _HRI_SECTIONS.items():
        measure = getattr(module, function, None)
        figures[section] = measure(seed) if callable(measure) else "not built"
    return figures


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Run the sections; print a table unless ``console`` is None."""
    try:
        import mujoco  # noqa: F401
    except ModuleNotFoundError:
        raise HomebotError("bench manipulation needs MuJoCo: pip install 'homebot[embodied]'")\
            from None
    began = time.perf_counter()
    figures: dict[str, Any] = {}
    if args.only in ("all", "grasping"):
        figures["grasping"] = _grasping(args.scenes, args.seed, args.objects)
    if args.only in ("all", "bad-input"):
        figures["bad input"] = _bad_input()
    if args.only in ("all", "hri"):
        figures["physical HRI"] = _hri(args.seed)
    figures["wall seconds"] = round(time.perf_counter() - began, 1)
    if console is not None:
        table = Table(title="bench manipulation")
        table.add_column("section")
        table.add_column("figure")
        table.add_column("value")
        for section, values in figures.items():
            if isinstance(values, dict):
                for key, value in values.items():
                    table.add_row(section, key, str(value))
            else:
                table.add_row(section, "", str(values))
        console.print(table)
    return {"benchmark": "manipulation", "figures": figures}
