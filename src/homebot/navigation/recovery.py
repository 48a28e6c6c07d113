"""Navigation with recovery: drive to a pose, and when the way is blocked, plan round it or wait.

``NavigateToPose`` alone gives up when it makes no headway. A robot among
people needs what Nav2's navigator wraps round its controller (replanning and
wait recoveries) and what CAESAR calls the dynamic obstacle extension: when the
robot makes no headway for ``stuck_after`` seconds, stage 1 plans again round
what the laser sees that the static map lacks (a person, a chair moved), with
what it saw lately remembered for a while; when there is no way round, the
robot waits for the way to clear, facing its way so that the laser sees who
left. Waiting with someone near (in a doorway they wait to pass through too),
it steps out of their way (``make_way``: out of doorways, round them) and
forgets what it no longer sees (Nav2's clear-costmap recovery). Someone standing
on the target itself: it comes as near as there is room and waits there. It
gives up when the time budget is spent.

Stage 1 by length alone squeezes through gaps that the local planner, keeping
its safety margin, can only crawl through, so a path with a margin from walls
and furniture is preferred wherever one exists.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from shapely.geometry import LineString

from homebot.errors import NavigationError
from homebot.geometry import Pose, from_frame, wrap_angle, wrap_angles
from homebot.navigation.localmap import LocalController
from homebot.navigation.navigate import (
    NavigateToPose,
    NavigationGoal,
    NavigationResult,
    StopReason,
)
from homebot.navigation.navigator import Navigator, polyline_length
from homebot.robot import Body, LaserScan, Twist

__all__ = ["NavigationAttempt", "ObstacleMemory", "RecoveringNavigation", "RecoveryPolicy",
           "scan_on_map"]

_STOP_TICKS = 60  #: control periods allowed beyond a goal's budget to come to rest
_FACE_AHEAD = 0.5  #: metres along the path to the point a spin recovery turns to face
_FACED = 0.3  #: radians: a spin recovery stops this close to facing that point
_DETOUR_BUDGETS = 3.0  #: a goal's whole time, detours included, in first budgets
#: metres nearer the target that end a wait: a squeeze that gets no nearer than this
#: keeps the patience running (it would otherwise restart with every narrow way tried)
_PROGRESS = 0.5
_AT_THE_MAP = 0.075  #: metres: a return this near a wall or furniture cell is that obstacle
_CLUSTER_JUMP = 0.1  #: metres between neighbouring returns of one thing
_NARROW_MARGIN = 0.05  #: metres from walls beyond the radius a narrow way keeps where it can
_SAME_THING = 0.07  #: metres between neighbouring returns of one remembered thing
_EXTENDED = 0.45  #: metres: a run of unexpected returns this long is no person's legs
# Making way (stepping aside for people who wait for the robot to pass):
_CROWDED = 1.5  #: metres: someone this near the waiting robot may be waiting for it in turn
_DOORWAY = 1.0  #: metres from a door's centre: no spot to step aside to
_MAKE_WAY_REACH = (0.6, 1.0, 1.4, 1.8)  #: metres from the robot, the spots tried
_MAKE_WAY_DIRECTIONS = 16
_MAKE_WAY_ROOM = 0.2  #: metres more than stage 1's margin round people, kept at the spot
_MAKE_WAY_FAR = 1.5  #: metres from people beyond which a spot is no better
_MAKE_WAY_PER_METRE = 0.3  #: a spot's score lost per metre of reach
_MAKE_WAY_TRIES = 6  #: best spots tried for a way there
_MAKE_WAY_DETOUR = 2.5  #: a way to a spot at most this many times its straight distance
_MAKE_WAY_TOLERANCE = 0.2  #: metres: near enough to the spot
_ROOM_CHECK_STEP = 0.05  #: metres between the points of a way checked to stay in the room


@dataclass(frozen=True)
class RecoveryPolicy:
    """How long to try, and how to plan round what the map lacks.

    Args:
        stuck_after: seconds without headway before planning again.
        seconds_per_metre: the time budget per metre of the first path ...
        wait_budget: ... plus this, for waiting and going round.
        obstacle_margin: metres kept from an unexpected return beyond the robot's radius.
        extended_margin: ... and from one of something long and flat the map lacks (a
            door's leaf left half open: it does not step into the way as people may, and
            past it a 0.8 m doorway leaves a 0.5 m robot little more than 0.6 m).
        static_margin: metres kept from walls and furniture beyond it, where there is room.
        obstacle_memory: seconds an unexpected return is remembered.
        unexplained: a return this much shorter than the static map explains is unexpected.
        wait: seconds to stand still when no way round exists.
        patience: seconds of waiting in a row, with no way round (or only narrow ways
            that bring the robot no nearer), before giving up as blocked (someone who
            stays in the way has to be asked to move).
        make_way_after: seconds of waiting, with someone near, before the robot steps
            out of their way (they may be waiting for it), and again after as long.
    """

    stuck_after: float = 3.0
    seconds_per_metre: float = 6.0
    wait_budget: float = 60.0
    # More than stage 2 keeps from a pair of legs (its safety plus leg margin), so that
    # stage 1 never offers a gap past a person that stage 2 will not drive through.
    obstacle_margin: float = 0.22
    extended_margin: float = 0.05
    static_margin: float = 0.14
    obstacle_memory: float = 45.0
    unexplained: float = 0.15
    wait: float = 3.0
    patience: float = 20.0
    make_way_after: float = 6.0

    def __post_init__(self) -> None:
        for name in ("stuck_after", "seconds_per_metre", "obstacle_memory", "unexplained",
                     "wait", "patience", "make_way_after"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise NavigationError(f"the recovery policy's {name} must be a positive "
                                      f"number, not {value!r}")
        for name in ("wait_budget", "obstacle_margin", "extended_margin", "static_margin"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise NavigationError(f"the recovery policy's {name} cannot be negative or "
                                      f"infinite, not {value!r}")


@dataclass
class ObstacleMemory:
    """Laser returns the static map does not explain, remembered for a while.

    Remembering keeps the robot from turning back to a way it has just seen
    blocked once the obstacle is out of its laser's sight; forgetting after a
    while lets people who walked off free the way again.
    """

    navigator: Navigator
    unexplained: float
    memory: float
    #: per point the last ``observe`` returned, whether it belongs to something long and
    #: flat (see ``unexpected_extended``)
    extended: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    _seen: list[tuple[float, np.ndarray]] = field(default_factory=list)

    def unexpected(self, pose: Pose, scan: LaserScan) -> np.ndarray:
        """The scan's returns, on the map by ``pose``, that no wall or furniture explains.

        A return far from every wall and piece of furniture is unexpected; so is
        one nearer to them (a person standing by a wall) when it comes back
        shorter, by more than ``unexplained``, than the map's obstacle along its
        beam. Returns right at the map's obstacles are always explained, as a
        beam grazing a wall may end a little early on a map raster.
        """
        points, unexplained = self._unexplained(pose, scan)
        unexpected: np.ndarray = points[unexplained]
        return unexpected

    def unexpected_extended(self, pose: Pose, scan: LaserScan) -> tuple[np.ndarray, np.ndarray]:
        """``unexpected(pose, scan)``, and per return whether it belongs to something long
        and flat the map lacks: a run of neighbouring unexpected returns at least
        ``_EXTENDED`` long (a door's leaf left half open, a box), which does not step
        into the way as a person may, and which no pair of legs makes."""
        points, unexplained = self._unexplained(pose, scan)
        beams = np.flatnonzero(scan.valid())
        extended = np.zeros(len(points), dtype=bool)
        # runs of unexpected returns on neighbouring beams, each step under a cluster's jump
        steps = np.hypot(*np.diff(points, axis=0).T) if len(points) > 1 else np.zeros(0)
        joined = (np.diff(beams) == 1) & (steps < _CLUSTER_JUMP) & unexplained[:-1] & \
            unexplained[1:]
        starts = np.flatnonzero(np.concatenate(([True], ~joined)))
        ends = np.concatenate((starts[1:], [len(points)])) - 1
        for start, end in zip(starts, ends, strict=True):
            if unexplained[start] and math.dist(points[start], points[end]) >= _EXTENDED:
                extended[start:end + 1] = True
        return points[unexplained], extended[unexplained]

    def _unexplained(self, pose: Pose, scan: LaserScan) -> tuple[np.ndarray, np.ndarray]:
        """The scan's returns on the map (beams with no return dropped), and which of them
        no wall or furniture explains."""
        keep = scan.valid()
        ranges = scan.ranges[keep]
        origin = _laser_origin(pose, scan)
        angles = scan.angles()[keep] + scan.mount.theta + pose.theta
        expected = self._expected_ranges(origin, angles, ranges + self.unexplained)
        points = scan_on_map(pose, scan)
        grid = self.navigator.grid
        rows, columns = grid.shape
        column = np.clip(((points[:, 0] - grid.origin[0]) / grid.resolution).astype(int),
                         0, columns - 1)
        row = np.clip(((points[:, 1] - grid.origin[1]) / grid.resolution).astype(int),
                      0, rows - 1)
        clearance = self.navigator.clearance()[row, column]
        short = (ranges < expected - self.unexplained) & (clearance > _AT_THE_MAP)
        return points, short | (clearance > self.unexplained)

    def _expected_ranges(self, origin: tuple[float, float], angles: np.ndarray,
                         reach: np.ndarray) -> np.ndarray:
        """Range to the first wall or furniture cell along each beam (inf within ``reach``)."""
        grid = self.navigator.grid
        step = grid.resolution / 2  # half a cell: a wall cell is never stepped over
        steps = np.arange(1, int(float(np.max(reach, initial=0.0)) / step) + 2) * step
        xs = origin[0] + np.multiply.outer(np.cos(angles), steps)
        ys = origin[1] + np.multiply.outer(np.sin(angles), steps)
        rows, columns = grid.shape
        column = ((xs - grid.origin[0]) / grid.resolution).astype(np.int64)
        row = ((ys - grid.origin[1]) / grid.resolution).astype(np.int64)
        inside = (column >= 0) & (column < columns) & (row >= 0) & (row < rows)
        solid = np.zeros(xs.shape, dtype=bool)
        solid[inside] = grid.occupied[row[inside], column[inside]]
        solid &= steps[None, :] <= reach[:, None]
        first = solid.argmax(axis=1)
        expected: np.ndarray = np.where(solid[np.arange(len(angles)), first], steps[first],
                                        np.inf)
        return expected

    def observe(self, now: float, pose: Pose, scan: LaserScan) -> np.ndarray:
        """Remember what the scan shows unexpected; everything remembered, as (n, 2).

        A remembered return that the scan now sees past (its beam reaches further)
        is gone, as a costmap clears the cells its rays cross: someone who stepped
        aside no longer blocks the way.
        """
        self._seen = [(seen, self._still_there(points, pose, scan))
                      for seen, points in self._seen if now - seen <= self.memory]
        points, extended = self.unexpected_extended(pose, scan)
        self._seen.append((now, np.column_stack((points, extended))))
        remembered = np.concatenate([points for _, points in self._seen])
        extended = remembered[:, 2] > 0
        if extended.any() and not extended.all():
            # The same leaf seen end on, or in pieces, from elsewhere: returns joined to a
            # long run by a chain of close neighbours belong to that one thing.
            pairs = cKDTree(remembered[:, :2]).query_pairs(_SAME_THING, output_type="ndarray")
            graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])),
                               shape=(len(remembered), len(remembered)))
            _, component = connected_components(graph, directed=False)
            extended = np.isin(component, component[extended])
        self.extended = extended
        return remembered[:, :2]

    def clear(self) -> None:
        """Forget everything remembered."""
        self._seen = []
        self.extended = np.zeros(0, dtype=bool)

    def _still_there(self, points: np.ndarray, pose: Pose, scan: LaserScan) -> np.ndarray:
        """The rows of ``points`` ((n, 2) or more columns, x and y first) that the scan
        does not see past."""
        if not len(points):
            return points
        origin_x, origin_y = _laser_origin(pose, scan)
        dx, dy = points[:, 0] - origin_x, points[:, 1] - origin_y
        distance = np.hypot(dx, dy)
        bearing = np.arctan2(dy, dx) - pose.theta - scan.mount.theta
        bearing = wrap_angles(bearing)
        beam = np.rint((bearing - scan.angle_min) / scan.angle_increment).astype(np.int64)
        seen = (beam >= 0) & (beam < len(scan.ranges))
        measured = np.full(len(points), -np.inf)
        ranges = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
        measured[seen] = ranges[beam[seen]]
        # Seen through: the beam passed it by a margin (and it is within the beam's reach).
        cleared = seen & (measured > distance + self.unexplained) & (distance < scan.range_max)
        kept: np.ndarray = points[~cleared]
        return kept


def _laser_origin(pose: Pose, scan: LaserScan) -> tuple[float, float]:
    """Where the laser stands on the map when the robot stands at ``pose``."""
    return pose.apply(scan.mount.x, scan.mount.y)


def scan_on_map(pose: Pose, scan: LaserScan) -> np.ndarray:
    """The scan's returns as (n, 2) map points, placed by ``pose``."""
    return from_frame(pose, scan.points())


@dataclass(frozen=True, slots=True)
class NavigationAttempt:
    """How a recovering navigation ended."""

    reached: bool
    reason: StopReason  #: REACHED, or why the last try stopped (BLOCKED, TIMEOUT, CANCELED)
    travelled: float  #: metres driven, by odometry
    duration: float  #: simulated seconds
    replans: int  #: times stage 1 planned round what the laser saw
    waits: int  #: times the robot stood waiting for the way to clear

    def __bool__(self) -> bool:
        return self.reached


class RecoveringNavigation:
    """Drive ``body`` to a target along stage-1 paths, recovering when blocked.

    Args:
        body: the robot's body.
        navigator: stage 1, on the static map.
        controller: stage 2, the local controller.
        localise: the pose estimate; called every control period (MCL updates there).
        policy: budgets and margins.
        on_replan: told each time stage 1 plans again (True: a way round was found).
    """

    def __init__(self, body: Body, navigator: Navigator, controller: LocalController,
                 localise: Callable[[], Pose], policy: RecoveryPolicy | None = None,
                 on_replan: Callable[[bool], None] | None = None) -> None:
        self.body = body
        self.navigator = navigator
        self.controller = controller
        self.localise = localise
        self.policy = policy or RecoveryPolicy()
        self.on_replan = on_replan
        self.memory = ObstacleMemory(navigator, self.policy.unexplained,
                                     self.policy.obstacle_memory)

    def drive(self, target: Pose, avoid_doors: frozenset[str] = frozenset(), *,
              tolerance: float = 0.15, heading_tolerance: float | None = 0.2,
              stop: Callable[[], bool] | None = None,
              near_enough: float = 0.0) -> NavigationAttempt:
        """Drive to ``target``; a path round ``avoid_doors`` only. ``stop`` is asked every
        control period (a person's stop gesture): True cancels the drive (CANCELED).
        With ``target`` taken by something the laser sees (a door's leaf over the spot
        where the robot would look at the door), coming as near as there is room counts
        as reaching it if that is within ``near_enough`` metres; else the robot waits.

        Raises:
            NavigationError: the static map has no path to the target at all.
        """
        body, policy = self.body, self.policy
        started = body.now()
        here = self.localise()
        plan = self.navigator.plan(here.xy(), target.xy(), avoid_doors)
        if plan is None:
            raise NavigationError(f"no path from ({here.x:.2f}, {here.y:.2f}) to "
                                  f"({target.x:.2f}, {target.y:.2f}) on the map")
        budget = plan.length * policy.seconds_per_metre + policy.wait_budget
        deadline = started + budget
        # A way round may be much longer than the first path: each one found earns its own
        # time per metre, up to a few first budgets in all.
        last_call = started + _DETOUR_BUDGETS * budget
        path: tuple[tuple[float, float], ...] | None = \
            self.plan_wide(here, target, avoid_doors, np.zeros((0, 2))) or plan.waypoints
        travelled, replans, waits = 0.0, 0, 0
        reason = StopReason.TIMEOUT
        waiting_since: float | None = None
        waiting_from = math.inf  #: metres from the target when the wait began
        made_way_at = -math.inf
        obstacles = np.zeros((0, 2))
        extended = np.zeros(0, dtype=bool)
        while body.now() < deadline:
            # Narrow ways tried meanwhile count as waiting too, unless they got it nearer.
            if waiting_since is not None and body.now() - waiting_since >= policy.patience:
                reason = StopReason.BLOCKED
                break
            if path is None:
                if waiting_since is None:
                    waiting_since = body.now()
                    waiting_from = math.dist(self.localise().xy(), target.xy())
                waits += 1
                if body.now() - max(waiting_since, made_way_at) >= policy.make_way_after:
                    made_way_at = body.now()
                    travelled += self.make_way(self.localise(), obstacles[~extended],
                                               avoid_doors)
                    # Nav2's clear-costmap recovery: what the laser cannot see from here
                    # (round a door's jamb, behind the robot) is no longer trusted; what
                    # still stands in view is seen again at once.
                    self.memory.clear()
                # Watch the way while waiting: the laser clears what it sees has gone.
                way = self.plan_wide(self.localise(), target, avoid_doors, np.zeros((0, 2)))
                if way is not None:
                    self._face(way)
                self._wait(policy.wait)
            else:
                budget = max(deadline - body.now(), body.tick_period)
                # Someone standing on the target: as near as the robot can come to it.
                aim = target if path[-1] == target.xy() else Pose(*path[-1], target.theta)
                goal = NavigationGoal(aim, path, tolerance, heading_tolerance, timeout=budget)
                action = NavigateToPose(goal, body, self.controller, self.localise,
                                        stuck_after=policy.stuck_after)
                result = _run(action, int(budget / body.tick_period) + _STOP_TICKS, stop)
                travelled += result.travelled
                reason = result.reason or StopReason.TIMEOUT
                if result.reached and aim is not target:
                    if math.dist(aim.xy(), target.xy()) <= near_enough:
                        reason = StopReason.REACHED
                        break
                    reason = StopReason.BLOCKED  # there: wait for the target to clear
                elif result.reached or reason is not StopReason.BLOCKED:
                    break
                else:
                    self._face(path)
            pose = self.localise()
            if waiting_since is not None and \
                    math.dist(pose.xy(), target.xy()) <= waiting_from - _PROGRESS:
                waiting_since = None  # on the way again
            obstacles = self.memory.observe(body.now(), pose, body.scan())
            extended = self.memory.extended
            # Waited a while for the wide way (people staying in it): a narrower way will do.
            squeeze = waiting_since is not None and \
                body.now() - waiting_since >= policy.make_way_after
            path = self.plan_wide(pose, target, avoid_doors, obstacles, squeeze, extended)
            if path is not None and path[-1] != target.xy() and \
                    math.dist(pose.xy(), path[-1]) <= tolerance:
                if math.dist(path[-1], target.xy()) <= near_enough:
                    reason = StopReason.REACHED
                    break
                path = None  # as near to an occupied target as it comes: wait there
            if path is not None:
                needed = body.now() + polyline_length(path) * policy.seconds_per_metre
                deadline = min(last_call, max(deadline, needed + policy.stuck_after))
            replans += 1
            if self.on_replan is not None:
                self.on_replan(path is not None)
        else:
            reason = StopReason.TIMEOUT
        return NavigationAttempt(reason is StopReason.REACHED, reason, round(travelled, 3),
                                 round(body.now() - started, 3), replans, waits)

    def plan_wide(self, here: Pose, target: Pose, avoid_doors: frozenset[str],
                  obstacles: np.ndarray, squeeze: bool = False,
                  extended: np.ndarray | None = None,
                  ) -> tuple[tuple[float, float], ...] | None:
        """Stage 1 round ``obstacles``, with a margin from walls and furniture.

        Through gaps narrower than the margin only when the static map itself has no
        wider way: when it has one and ``obstacles`` stand in it, None (wait, or ask),
        rather than squeezing through a gap the local planner can only crawl through;
        unless ``squeeze`` (the robot has waited for the wide way a while already).
        ``extended`` marks the obstacles of something long and flat (a door's leaf),
        from which the policy's ``extended_margin`` is kept instead.
        """
        radius, policy = self.body.radius, self.policy
        around, wide = radius + policy.obstacle_margin, radius + policy.static_margin
        flat = np.zeros((0, 2))
        if extended is not None and extended.any():
            obstacles, flat = obstacles[~extended], obstacles[extended]
        beside = radius + policy.extended_margin
        # Someone standing on the target itself: the path ends as near to it as there is
        # room (the robot waits there for them to step off).
        near = around
        path = self.navigator.plan_around(here.xy(), target.xy(), avoid_doors, obstacles,
                                          around, wide, near_goal=near, flat=flat,
                                          flat_clearance=beside)
        if path is not None:
            return path
        # People may step out of the wide way; what is long and flat (a leaf) will not.
        if len(obstacles) and not squeeze and self.navigator.plan_around(
                here.xy(), target.xy(), avoid_doors, np.zeros((0, 2)), around, wide,
                flat=flat, flat_clearance=beside):
            return None
        # The narrow way: a little room from walls where there is, else the radius.
        for static in (radius + _NARROW_MARGIN, None):
            path = self.navigator.plan_around(here.xy(), target.xy(), avoid_doors, obstacles,
                                              around, static, near_goal=near, flat=flat,
                                              flat_clearance=beside)
            if path is not None:
                return path
        return None

    def make_way(self, here: Pose, obstacles: np.ndarray, avoid_doors: frozenset[str]) -> float:
        """Step out of the way of people standing round the robot (metres driven).

        Waiting in a doorway or a narrow passage for someone who waits for the robot in
        turn (they cannot pass it either) waits for ever: as people do, and as Nav2's
        back-up recovery does, the robot steps aside, out of doorways and away from
        whoever stands near, to a free spot it can reach round them, and waits there
        for the way to clear. Nothing to step away from, or nowhere to go: 0.
        """
        body, policy, navigator = self.body, self.policy, self.navigator
        if not len(obstacles):
            return 0.0
        distance = np.hypot(obstacles[:, 0] - here.x, obstacles[:, 1] - here.y)
        if float(distance.min()) > _CROWDED:
            return 0.0
        around, wide = body.radius + policy.obstacle_margin, body.radius + policy.static_margin
        world = navigator.world
        doors = [door.position for door in world.doors.values()]
        # Aside within the room the robot is in (either room, standing in a doorway): a
        # spot back through a doorway it has just come through would be a shuttle.
        rooms = self._rooms_beside(here)
        spots: list[tuple[float, tuple[float, float]]] = []
        for reach in _MAKE_WAY_REACH:
            for turn in range(_MAKE_WAY_DIRECTIONS):
                angle = math.tau * turn / _MAKE_WAY_DIRECTIONS
                spot = (here.x + reach * math.cos(angle), here.y + reach * math.sin(angle))
                if world.room_at(*spot) not in rooms \
                        or navigator.clearance_at(*spot) < wide \
                        or any(math.dist(spot, door) < _DOORWAY for door in doors):
                    continue
                away = float(np.min(np.hypot(obstacles[:, 0] - spot[0],
                                             obstacles[:, 1] - spot[1])))
                if away < around + _MAKE_WAY_ROOM:
                    continue
                spots.append((min(away, _MAKE_WAY_FAR) - _MAKE_WAY_PER_METRE * reach, spot))
        for _, spot in sorted(spots, reverse=True)[:_MAKE_WAY_TRIES]:
            path = navigator.plan_around(here.xy(), spot, avoid_doors, obstacles, around, wide)
            if path is None or polyline_length(path) > _MAKE_WAY_DETOUR * math.dist(
                    here.xy(), spot) or any(world.room_at(*point) not in rooms
                                            for point in _densified(path, _ROOM_CHECK_STEP)):
                continue
            self._face(path)
            length = polyline_length(path)
            budget = length * policy.seconds_per_metre + policy.stuck_after
            goal = NavigationGoal(Pose(*spot, here.theta), path, _MAKE_WAY_TOLERANCE, None,
                                  timeout=budget)
            action = NavigateToPose(goal, body, self.controller, self.localise,
                                    stuck_after=policy.stuck_after)
            return action.run(int(budget / body.tick_period) + _STOP_TICKS).travelled
        return 0.0

    def _rooms_beside(self, here: Pose) -> set[str | None]:
        """The room the robot stands in; standing in a doorway (its disc across the
        wall's line), both of that door's rooms."""
        world = self.navigator.world
        rooms: set[str | None] = {world.room_at(here.x, here.y)}
        across_the_line = self.body.radius + world.model.wall_thickness / 2
        for name, door in world.doors.items():
            nx, ny = world.door_normal(name)
            dx, dy = here.x - door.position[0], here.y - door.position[1]
            if abs(dx * nx + dy * ny) < across_the_line and \
                    abs(dx * ny - dy * nx) < door.width / 2:
                rooms.update(door.rooms)
        rooms.discard(None)
        return rooms

    def _face(self, path: tuple[tuple[float, float], ...]) -> None:
        """Turn on the spot to face along ``path`` (Nav2's spin recovery): a local
        planner caught facing away from its way may find none it can start on."""
        self.face(_point_along(path, self.localise().xy(), _FACE_AHEAD))

    def face(self, point: tuple[float, float]) -> None:
        """Turn on the spot until ``point`` lies straight ahead (within a few degrees)."""
        body = self.body
        pose = self.localise()
        for _ in range(int(2 * math.pi / (body.limits.angular * body.tick_period)) + 1):
            error = wrap_angle(math.atan2(point[1] - pose.y, point[0] - pose.x) - pose.theta)
            if abs(error) <= _FACED:
                break
            limit = math.sqrt(2 * body.limits.angular_acceleration * abs(error))
            body.command_velocity(Twist(0.0, 0.0, math.copysign(
                min(body.limits.angular, limit), error)))
            body.tick()
            pose = self.localise()
        body.command_velocity(Twist())

    def _wait(self, seconds: float) -> None:
        """Come to rest and stand still for ``seconds`` (someone may move out of the way)."""
        body = self.body
        body.command_velocity(Twist())
        body.tick(max(1, int(seconds / body.tick_period)))


def _run(action: NavigateToPose, steps: int, stop: Callable[[], bool] | None
         ) -> NavigationResult:
    """``action.run(steps)``, cancelled as soon as ``stop`` says so."""
    if stop is None:
        return action.run(steps)
    for _ in range(steps):
        if stop():
            action.cancel()
        if action.step().done:
            return action.result()
    return action.run(0)  # out of steps: aborted, as run does


def _densified(path: tuple[tuple[float, float], ...], step: float
               ) -> list[tuple[float, float]]:
    """The points of ``path`` with points put between them at most ``step`` metres apart."""
    if len(path) < 2:
        return list(path)
    return [(x, y) for x, y in LineString(path).segmentize(step).coords]


def _point_along(path: tuple[tuple[float, float], ...], here: tuple[float, float],
                 distance: float) -> tuple[float, float]:
    """The point ``distance`` metres along ``path`` past its point nearest to ``here``."""
    nearest = min(range(len(path)), key=lambda index: math.dist(path[index], here))
    point, left = here, distance
    for waypoint in path[nearest + 1:] or path[-1:]:
        step = math.dist(point, waypoint)
        if step >= left:
            t = left / step
            return (point[0] + t * (waypoint[0] - point[0]),
                    point[1] + t * (waypoint[1] - point[1]))
        point, left = waypoint, left - step
    return point
