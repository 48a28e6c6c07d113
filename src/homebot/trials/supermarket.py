"""Supermarket trials: seeded misplaced and missing products, and a referee of each request.

``random_supermarket`` draws where the assistant left every product; ``run_world`` serves
the same seeded requests with the inference cycle, with it but no put-backs, and with a
fixed-order search, counting shelf visits with ``ShelfVisitCounter`` (a simulated robot
that counts them) and judging each outcome and the knowledge base against the
simulator's truth. ``homebot bench inference`` runs many worlds and prints the figures.
"""

from __future__ import annotations

import random
import typing
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from homebot.cancel import CancelToken
from homebot.executive import Executive, RunReport
from homebot.executive.recovery import Protocol, StepRunner
from homebot.geometry import Pose
from homebot.inference import InferenceCycle, Inventory, fetch_task
from homebot.knowledge import KnowledgeBase
from homebot.robot import Detection, MoveReport
from homebot.sim import Responder, SimRobot, Simulation
from homebot.skills import ErrorCode, Outcome, SkillContext
from homebot.task import Step, Task
from homebot.world import PersonModel, World

__all__ = ["BuiltRun", "RunParts", "ShelfVisitCounter", "SupermarketTrial", "WorldResult",
           "fixed_order_search", "random_supermarket", "run_world"]


class ShelfVisitCounter(SimRobot):
    """A simulated robot that counts its visits to shelves.

    A search visit is an arrival at a shelf followed first by a look; an arrival
    followed first by putting something down is a put-back visit.
    """

    def __init__(self, simulation: Simulation, shelves: set[str]) -> None:
        super().__init__(simulation)
        self.shelves = shelves
        self.visits: list[str] = []
        self.put_back_visits = 0
        self._arrived = True
        self.expect()

    def move_to(self, goal: Pose, avoid_doors: frozenset[str] = frozenset(),
                escort: str | None = None, *,
                cancel: CancelToken | None = None) -> MoveReport:
        self._arrived = True
        return super().move_to(goal, avoid_doors, escort, cancel=cancel)

    def expect(self, *products: str | None) -> None:
        """Count the visits until one of ``products`` is grasped (a new request)."""
        self.wanted = {p for p in products if p}
        self.until_grasp: int | None = None
        self._start = len(self.visits)

    def visits_until_grasp(self) -> int:
        """Shelves visited for the current request until the product was in hand."""
        last = self.until_grasp if self.until_grasp is not None else len(self.visits)
        return last - self._start

    def grasp(self, detection: Detection, hand: str) -> None:
        super().grasp(detection, hand)
        if (self.until_grasp is None and detection.label in self.wanted
                and self.held(hand) is not None):
            self.until_grasp = len(self.visits)

    def release(self, hand: str, placement: str) -> None:
        if self._arrived and placement in self.shelves:
            self.put_back_visits += 1
            self._arrived = False
        super().release(hand, placement)

    def perceive_objects(self, placement: str) -> list[Any]:
        if self._arrived and placement in self.shelves:
            self.visits.append(placement)
            self._arrived = False
        return super().perceive_objects(placement)


def random_supermarket(world: World, inventory: Inventory, seed: int, misplaced: float,
                       missing: float) -> dict[str, str | None]:
    """Where the assistant left each product (None: ran out), drawn from ``seed``."""
    rng = random.Random(seed)
    shelves = [inventory.place(s) for s in inventory.shelves]
    truth: dict[str, str | None] = {}
    for product in sorted(world.objects):
        home = world.objects[product].placement
        draw = rng.random()
        if draw < missing:
            truth[product] = None
        elif draw < missing + misplaced:
            truth[product] = rng.choice([s for s in shelves if s != home])
        else:
            truth[product] = home
    return truth


def _agreeable(person: PersonModel, question: str) -> str | None:
    return "yes please" if "instead" in question.lower() else None


def fixed_order_search(order: list[str]) -> Protocol:
    """The baseline: on a failed take, look on every shelf in a fixed order."""
    def protocol(context: SkillContext, skill: str, args: Mapping[str, Any], outcome: Outcome,
                 run: StepRunner) -> bool | Outcome:
        wanted = str(args.get("object", ""))
        if skill != "pick" or outcome.error is not ErrorCode.NOT_FOUND:
            return False
        for place in order:
            context.bindings[f"placement:{wanted}"] = place
            taken = run("pick", {"object": wanted}, recover=False)
            if taken:
                return taken
        return Outcome.failed(ErrorCode.NOT_FOUND, f"no shelf has the {wanted}")
    return protocol


@dataclass
class WorldResult:
    """What happened in one world, for both robots."""

    right: int = 0  #: requests ending as they should (delivered, or the right alternative)
    requests: int = 0
    absent: int = 0  #: requests for products that had run out
    kb_consistent: bool = True
    visits: list[int] = field(default_factory=list)  #: shelf visits per request, inference
    search_visits: list[int] = field(default_factory=list)  #: the same, r_max = 0
    visits_to_grasp: list[int] = field(default_factory=list)  #: until the product is in hand
    baseline_to_grasp: list[int] = field(default_factory=list)
    put_back_visits: int = 0  #: visits to shelves to put something back (requests only)
    baseline_visits: list[int] = field(default_factory=list)
    baseline_right: int = 0
    sim_time: float = 0.0
    put_back: int = 0


@dataclass(frozen=True)
class SupermarketTrial:
    """How a seeded supermarket is drawn and served."""

    requests: int = 3  #: client requests per world
    misplaced: float = 0.3  #: chance that the assistant put a product on a wrong shelf
    missing: float = 0.1  #: chance that a product ran out
    r_max: float = 240.0  #: the inference cycle's decision budget (s)
    noise: float = 0.0  #: disturbance level (0: only the assistant's misplacements)


class BuiltRun(typing.Protocol):
    """What the trial uses of a run (``homebot.app.Run`` is one)."""

    @property
    def simulation(self) -> Simulation: ...

    @property
    def context(self) -> SkillContext: ...

    @property
    def executive(self) -> Executive: ...


#: Builds a run in the trial's world for ``seed``, with ``inference`` as its recovery
#: protocol of last resort, ``responder`` answering for the people, and disturbances at
#: ``noise`` (0: none). The caller's, since ``homebot.app`` wires runs.
RunParts = Callable[[int, Protocol, Responder, float], BuiltRun]


@dataclass
class _Served:
    """A run's parts, with the shelf-visit counter as its robot."""

    simulation: Simulation
    context: SkillContext
    executive: Executive
    robot: ShelfVisitCounter

    def run(self, task: Task) -> RunReport[None]:
        return self.executive.run(task)


def run_world(world: World, seed: int, trial: SupermarketTrial, kb_text: str,
              build: RunParts) -> WorldResult:
    """One seeded supermarket: the same requests served with the cycle and with the baseline,
    each in a run ``build`` makes."""
    inventory = Inventory(KnowledgeBase.from_text(kb_text))
    truth = random_supermarket(world, inventory, seed, trial.misplaced, trial.missing)
    requests = random.Random(seed + 1).sample(sorted(world.objects), trial.requests)
    result = WorldResult(requests=len(requests))
    shelves = {inventory.place(s) for s in inventory.shelves}

    cycle = InferenceCycle(inventory, r_max=trial.r_max, seed=seed)
    simulated, robot = _simulated(build, seed, truth, cycle, shelves, trial.noise)
    for product in requests:
        present = _available(simulated.simulation.object_location.get(product), shelves)
        substitute = inventory.substitute(product)
        substitute_there = _available(
            simulated.simulation.object_location.get(substitute or ""), shelves)
        result.absent += not present
        before = len(robot.visits)
        robot.expect(product, substitute)
        report = simulated.run(fetch_task(inventory, product))
        result.visits.append(len(robot.visits) - before)
        result.visits_to_grasp.append(robot.visits_until_grasp())
        result.put_back_visits = robot.put_back_visits
        given = [str(s.args["object"]) for s in report.steps
                 if s.skill == "give" and s.status == "verified"]
        for name in given:
            cycle.handed_over(name)
        with_client = simulated.simulation.object_location
        if present:
            result.right += given == [product] and with_client[product] == "person:customer"
        elif substitute is not None and substitute_there:
            result.right += given == [substitute]
        else:
            result.right += not given and inventory.out_of_stock(product)
        result.put_back += len(cycle.tidy_up(simulated.context,  # idle time
                                             run=simulated.executive.run_step))
    result.kb_consistent = _kb_agrees(inventory, cycle, simulated.simulation, shelves)
    result.sim_time = simulated.robot.now()

    quiet = InferenceCycle(Inventory(KnowledgeBase.from_text(kb_text)), r_max=0.0,
                           seed=seed)  # no put-backs while a client waits
    searching, searcher = _simulated(build, seed, truth, quiet, shelves,
                                      trial.noise)
    for product in requests:
        before = len(searcher.visits)
        report = searching.run(fetch_task(quiet.inventory, product))
        result.search_visits.append(len(searcher.visits) - before)
        for step in report.steps:
            if step.skill == "give" and step.status == "verified":
                quiet.handed_over(str(step.args["object"]))

    baseline, counter = _simulated(build, seed, truth,
                                   fixed_order_search(sorted(shelves)), shelves, trial.noise)
    for product in requests:
        present = _available(baseline.simulation.object_location.get(product), shelves)
        before = len(counter.visits)
        counter.expect(product)
        report = baseline.run(Task((Step("pick", {"object": product}),
                                    Step("navigate", {"to": "operator"}),
                                    Step("give", {"person": "operator", "object": product}))))
        result.baseline_visits.append(len(counter.visits) - before)
        result.baseline_to_grasp.append(counter.visits_until_grasp())
        result.baseline_right += report.success == present
    return result


def _available(where: str | None, shelves: set[str]) -> bool:
    return where is not None and (where in shelves or where.startswith("hand:"))


def _simulated(build: RunParts, seed: int, truth: Mapping[str, str | None],
               protocol: Protocol, shelves: set[str],
               noise: float = 0.0) -> tuple[_Served, ShelfVisitCounter]:
    built = build(seed, protocol, _agreeable, noise)
    simulation, context, executive = built.simulation, built.context, built.executive
    simulation.object_location.update(truth)
    robot = ShelfVisitCounter(simulation, shelves)
    context.robot = robot
    return _Served(simulation, context, executive, robot), robot


def _kb_agrees(inventory: Inventory, cycle: InferenceCycle, simulation: Simulation,
               shelves: set[str]) -> bool:
    """Every shelf the robot saw holds what the KB says; what ran out is gone; sold is sold."""
    truth = simulation.object_location
    for shelf in cycle.previous_shelves:
        place = inventory.place(shelf)
        really = {p for p, where in truth.items() if where == place}
        believed = {p for p in inventory.products if inventory.believed_at(p) == shelf}
        if really != believed:
            return False
    for product in inventory.products:
        if inventory.out_of_stock(product) and truth.get(product) in shelves:
            return False
        if inventory.believed_at(product) == "customer" and (
                truth.get(product) != "person:customer"):
            return False
    return True
