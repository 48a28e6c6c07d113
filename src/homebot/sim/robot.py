"""``SimRobot``: the Robot port over the simulation, with sensors that can be wrong."""

from __future__ import annotations

import math

from homebot.cancel import CancelToken
from homebot.geometry import Pose
from homebot.robot import Blocker, Detection, HelpRequest, MoveReport, PersonPercept, Robot
from homebot.sim.simulation import HAND_PREFIX, PERSON_PREFIX, Simulation
from homebot.world import DoorState

__all__ = ["ActionDurations", "SimRobot"]


class ActionDurations:
    """Simulated seconds each action takes (motion time follows path length and speed)."""

    LOOK = 2.0
    GRASP = 8.0
    RELEASE = 5.0
    HAND_OVER = 4.0
    OPEN_DOOR = 6.0
    SECONDS_PER_WORD = 0.3
    LISTEN = 3.0
    TURN = 1.0
    FOLLOW_SPEED = 0.6


# How close the robot must be to use a placement, reach a person or a door (metres).
_REACH_PLACEMENT = 0.6
_REACH_PERSON = 2.0
_REACH_DOOR = 1.5
_STOP_BEFORE_DOOR = 0.6


class SimRobot(Robot):
    """A robot body in a ``Simulation``. All its reports come from simulated sensors."""

    def __init__(self, simulation: Simulation) -> None:
        self.sim = simulation

    @property
    def hands(self) -> tuple[str, ...]:
        return tuple(self.sim.hands)

    def now(self) -> float:
        return self.sim.clock.now()

    def pose(self) -> Pose:
        return Pose(*self.sim.robot_pose)

    # ------------------------------------------------------------ motion

    def move_to(self, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *,
                cancel: CancelToken | None = None) -> MoveReport:
        sim = self.sim
        start = sim.robot_pose[:2]
        plan = sim.plans.plan(start, goal.xy(), avoid_doors)
        if plan is None:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
        shut = sim.closed_doors()
        for index, door in enumerate(plan.doors):
            if door not in shut:
                continue
            stop = sim.world.point_before_door(door, plan.route.rooms[index],
                                               _STOP_BEFORE_DOOR).xy()
            travelled = sim.navigator.distance(start, stop, avoid_doors)
            travelled = plan.length if math.isinf(travelled) else travelled
            if not self._travel(travelled, stop, escort, cancel=cancel):
                return MoveReport(False, self.pose(), 0.0, Blocker.CANCELLED)
            self._trail([stop])
            blocker_person = next((name for name, p in sim.people.items()
                                   if p.blocking_door == door), None)
            blocker = Blocker.PERSON if blocker_person and sim.door_state[door] is \
                DoorState.OPEN else Blocker.DOOR_CLOSED
            sim.events.record("sim.blocked", door=door, blocker=blocker.value)
            return MoveReport(False, self.pose(), travelled, blocker, door,
                              blocker_person if blocker is Blocker.PERSON else None,
                              plan.doors[:index])
        if not self._travel(plan.length, goal.xy(), escort, goal.theta, cancel=cancel):
            return MoveReport(False, self.pose(), 0.0, Blocker.CANCELLED)
        self._trail(plan.waypoints[1:])
        return MoveReport(True, self.pose(), plan.length, doors_passed=plan.doors)

    def _trail(self, points: list[tuple[float, float]] | tuple[tuple[float, float], ...]) -> None:
        rounded = [(round(x, 3), round(y, 3)) for x, y in points]
        trail = self.sim.trail
        trail.extend(rounded)
        keep = self.sim.trail_keep
        if keep is not None and len(trail) > 2 * keep:
            del trail[:len(trail) - keep]
        self.sim.events.record("robot.path", world=self.sim.world.name,
                               points=[list(point) for point in rounded])

    def _travel(self, distance: float, point: tuple[float, float], escort: str | None,
                theta: float | None = None, *, cancel: CancelToken | None = None) -> bool:
        """Drive ``distance`` to ``point``; False when cancelled on the way. The symbolic
        robot arrives at the end of its drive, so a cancelled drive leaves it where it
        started."""
        sim = self.sim
        heading = sim.robot_pose[2] if theta is None else theta
        sim.clock.advance(distance / sim.world.robot.speed + ActionDurations.TURN,
                          cancel=cancel)
        if cancel is not None and cancel.cancelled:
            return False
        sim.robot_pose = (point[0], point[1], heading)
        if escort and escort in sim.people:
            sim.move_person(escort, (point[0] - 0.6 * math.cos(heading),
                                     point[1] - 0.6 * math.sin(heading)))
        return True

    def follow(self, person: str, goal: Pose | None, *,
               cancel: CancelToken | None = None) -> MoveReport:
        sim = self.sim
        state = sim.person_state(person)
        if state is None or sim.distance_to(state.position) > _REACH_PERSON:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
        destination = goal.xy() if goal else state.position
        plan = sim.plans.plan(sim.robot_pose[:2], destination)
        if plan is None:
            return MoveReport(False, self.pose(), 0.0, Blocker.NO_PATH)
        sim.move_person(person, destination)
        # People open doors on their way; the robot follows them through.
        for door in plan.doors:
            if sim.door_state[door] is DoorState.CLOSED:
                sim.door_state[door] = DoorState.OPEN
        sim.clock.advance(plan.length / ActionDurations.FOLLOW_SPEED, cancel=cancel)
        if cancel is not None and cancel.cancelled:  # the person walked on; the robot stood
            return MoveReport(False, self.pose(), 0.0, Blocker.CANCELLED)
        behind = plan.waypoints[-2] if len(plan.waypoints) > 1 else destination
        dx, dy = destination[0] - behind[0], destination[1] - behind[1]
        norm = math.hypot(dx, dy) or 1.0
        stop = (destination[0] - dx / norm * 0.8, destination[1] - dy / norm * 0.8)
        if sim.world.room_at(*stop) is None:
            stop = behind
        sim.robot_pose = (stop[0], stop[1], math.atan2(dy, dx))
        self._trail([*plan.waypoints[1:-1], stop])
        return MoveReport(True, self.pose(), plan.length, doors_passed=plan.doors)

    # ------------------------------------------------------------ perception

    def perceive_objects(self, placement: str) -> list[Detection]:
        sim = self.sim
        sim.clock.advance(ActionDurations.LOOK)
        where = sim.world.placements.get(placement)
        if where is None or sim.distance_to(where.approach.xy()) > _REACH_PLACEMENT:
            return []
        sim.maybe_move_during_task(placement)
        detections = []
        model = sim.disturbances
        for name in sim.objects_on(placement):
            obj = sim.world.objects[name]
            draw = sim.random.random()
            if draw < model.detection_miss:
                continue
            label = name
            if draw < model.detection_miss + model.detection_confusion:
                lookalikes = sorted(other for other, o in sim.world.objects.items()
                                    if o.category == obj.category and other != name)
                label = sim.random.choice(lookalikes) if lookalikes else name
            detections.append(Detection(label, obj.category, sim.object_ids[name],
                                        sim.position_on(name, placement)))
        return detections

    def perceive_people(self) -> list[PersonPercept]:
        sim = self.sim
        sim.clock.advance(ActionDurations.LOOK)
        room = sim.robot_room()
        seen = []
        for name, state in sorted(sim.people.items()):
            if state.room != room:
                continue
            if sim.random.random() < sim.disturbances.detection_miss:
                continue
            model = state.model
            seen.append(PersonPercept(name, state.posture.value, model.gesture.value,
                                      tuple(model.clothes), state.position, state.room))
        return seen

    # ------------------------------------------------------------ manipulation

    def grasp(self, detection: Detection, hand: str) -> None:
        sim = self.sim
        sim.clock.advance(ActionDurations.GRASP)
        name = sim.object_by_id(detection.handle)
        if name is None or sim.hands.get(hand, "busy") is not None:
            return
        where = sim.object_location[name]
        placement = sim.world.placements.get(where or "")
        if placement is None or sim.distance_to(placement.approach.xy()) > _REACH_PLACEMENT:
            return  # the object is not within reach: the hand closes on nothing
        if sim.random.random() < sim.disturbances.grasp_slip:
            sim.events.record("sim.disturbance", what="grasp_slip", object=name)
            return
        sim.hands[hand] = name
        sim.handled.add(name)
        sim.object_location[name] = HAND_PREFIX + hand

    def held(self, hand: str) -> Detection | None:
        name = self.sim.hands.get(hand)
        if name is None:
            return None
        return Detection(name, self.sim.world.objects[name].category, self.sim.object_ids[name])

    def release(self, hand: str, placement: str) -> None:
        sim = self.sim
        sim.clock.advance(ActionDurations.RELEASE)
        name = sim.hands.get(hand)
        if name is None:
            return
        where = sim.world.placements.get(placement)
        reachable = where is not None and sim.distance_to(where.approach.xy()) <= _REACH_PLACEMENT
        sim.hands[hand] = None
        sim.object_location[name] = placement if reachable else f"floor:{sim.robot_room()}"

    def hand_over(self, hand: str, person: str) -> bool:
        sim = self.sim
        sim.clock.advance(ActionDurations.HAND_OVER)
        name = sim.hands.get(hand)
        state = sim.person_state(person)
        if name is None or state is None or sim.distance_to(state.position) > _REACH_PERSON:
            return False
        sim.hands[hand] = None
        sim.object_location[name] = PERSON_PREFIX + person
        return True

    def receive(self, hand: str, person: str) -> Detection | None:
        sim = self.sim
        sim.clock.advance(ActionDurations.HAND_OVER)
        state = sim.person_state(person)
        if sim.hands.get(hand, "busy") is not None or state is None or \
                sim.distance_to(state.position) > _REACH_PERSON:
            return None
        given = sorted(name for name, where in sim.object_location.items()
                       if where == PERSON_PREFIX + person)
        if not given:
            return None
        sim.hands[hand] = given[0]
        sim.handled.add(given[0])
        sim.object_location[given[0]] = HAND_PREFIX + hand
        return self.held(hand)

    def open_door(self, door: str) -> bool:
        sim = self.sim
        sim.clock.advance(ActionDurations.OPEN_DOOR)
        if door not in sim.door_state or \
                sim.distance_to(sim.world.doors[door].position) > _REACH_DOOR:
            return False
        if sim.door_state[door] is DoorState.CLOSED:
            sim.door_state[door] = DoorState.OPEN
        return sim.door_state[door] is DoorState.OPEN

    def door_is_open(self, door: str) -> bool | None:
        sim = self.sim
        if door not in sim.door_state or \
                sim.distance_to(sim.world.doors[door].position) > _REACH_DOOR:
            return None
        return sim.door_state[door] is DoorState.OPEN

    # ------------------------------------------------------------ interaction

    def say(self, text: str) -> None:
        self.sim.clock.advance(ActionDurations.SECONDS_PER_WORD * max(1, len(text.split())))
        self.sim.events.record("sim.speech", text=text)

    def ask(self, person: str, question: str) -> str | None:
        sim = self.sim
        self.say(question)
        sim.clock.advance(ActionDurations.LISTEN)
        state = sim.person_state(person)
        if state is None or sim.distance_to(state.position) > _REACH_PERSON:
            return None
        return sim.responder(state.model, question)

    def _addressed(self, door: str) -> str:
        """Who hears a request made to nobody by name: whoever stands nearest ``door``
        (or, with no door, the robot); "" for nobody."""
        sim = self.sim
        model = sim.world.doors.get(door)
        where = model.position if model is not None else sim.robot_pose[:2]
        near = sorted((math.dist(state.position, where), name)
                      for name, state in sim.people.items())
        return near[0][1] if near else ""

    def request(self, person: str, request: HelpRequest, target: str) -> bool:
        sim = self.sim
        sim.clock.advance(ActionDurations.LISTEN)
        person = person or self._addressed(target)
        state = sim.person_state(person)
        if state is None or sim.distance_to(state.position) > _REACH_PERSON + 1.0:
            return False
        if not state.model.cooperative:
            return False
        if request is HelpRequest.STEP_ASIDE:
            return sim.step_aside(person, target)
        if request is HelpRequest.OPEN_DOOR and target in sim.door_state:
            sim.clock.advance(ActionDurations.OPEN_DOOR)
            sim.door_state[target] = DoorState.OPEN
            return True
        return False
