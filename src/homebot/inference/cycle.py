"""``InferenceCycle``: diagnosis, decision and planning on demand, as an executive protocol."""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from homebot.executive.recovery import StepRunner
from homebot.inference.decision import Decision, Rewards, decide
from homebot.inference.diagnosis import Diagnosis, diagnose
from homebot.inference.inventory import CUSTOMER, ROBOT, Inventory
from homebot.inference.observation import (
    Observation,
    PutBack,
    fulfil_cognitive_obligations,
    listing,
    observe,
)
from homebot.inference.planning import HAND, USER, ActionModel, BasicAction, Carry, Plan
from homebot.skills import ErrorCode, Outcome, SkillContext, speak
from homebot.skills.places import near, resolve_target

__all__ = ["CycleRecord", "InferenceCycle"]

_ROBOT = "robot"  # the robot's own position, as a location name for distances
_YES = ("yes", "sure", "ok", "okay", "please", "yeah", "of course")


@dataclass(frozen=True, slots=True)
class CycleRecord:
    """One turn of the cycle: its goal, diagnosis, decision and how its plan ended."""

    goal: str
    diagnosis: Diagnosis
    decision: Decision | None
    ended: str  #: taken, surprise, ran_out, failed

    def to_dict(self) -> dict[str, Any]:
        plan = self.decision.plan if self.decision else None
        return {"goal": self.goal, "ended": self.ended,
                "assumed": {p: self.diagnosis.location[p] for p in sorted(self.diagnosis.assumed)},
                "ran_out": sorted(self.diagnosis.ran_out),
                "decision": [c.product for c in self.decision.chosen] if self.decision else [],
                "plan": [str(a) for a in plan.actions] if plan else [],
                "plan_cost": round(plan.cost, 1) if plan else None}


class InferenceCycle:
    """The daily-life inference cycle, plugged in as ``build_run(RunSettings(inference=cycle))``.

    Called by the executive when a ``pick`` or ``find_object`` ends ``not_found``,
    it observes the shelf, diagnoses where things must be, decides which
    obligations to serve within ``r_max`` seconds, plans, and executes the plan
    through skills until the sought product is in hand (the executive then
    delivers it); a look that refutes the diagnosis starts the next turn. When no
    shelf can hold the product any more, the supermarket ran out of it: the KB
    says so, the manager gets a message, and the product's substitute is fetched
    and offered. ``Previous_Shelves`` and ``Objects_Placed`` persist over the
    session, so later requests profit from what earlier ones saw.
    """

    def __init__(self, inventory: Inventory | None = None, *, r_max: float = 240.0,
                 seed: int = 0, client: str = "operator", model: ActionModel | None = None,
                 rewards: Rewards | None = None, max_turns: int = 8,
                 offer_alternatives: bool = True) -> None:
        self.inventory = inventory or Inventory.load()
        self.r_max = r_max
        self.client = client
        self.model = model or _model_from(self.inventory)
        self.rewards = rewards or Rewards()
        self.max_turns = max_turns
        self.offer_alternatives = offer_alternatives
        self.rng = random.Random(seed)
        self.previous_shelves: dict[str, set[str]] = {}  #: shelf → products on it now
        self.objects_placed: list[str] = []
        self.pending: dict[str, PutBack] = {}  #: Pending_Task: product → put-back obligation
        self.robot_moved: dict[str, str] = {}  #: product → shelf the assistant had put it on
        self.delivered: set[str] = set()
        self.messages: list[str] = []  #: text messages to the manager
        self.records: list[CycleRecord] = []
        self.diagnosis: Diagnosis | None = None

    # -- the protocol --------------------------------------------------------------------------

    def __call__(self, context: SkillContext, skill: str, args: Mapping[str, Any],
                 outcome: Outcome, run: StepRunner) -> bool | Outcome:
        """Take over a take behaviour that did not find its product; else decline (False)."""
        goal = str(args.get("object", ""))
        if (skill not in ("pick", "find_object") or outcome.error is not ErrorCode.NOT_FOUND
                or goal not in self.inventory.products):
            return False
        shelf = self.inventory.shelf_at(str(outcome.data.get("placement") or ""))
        if shelf is None and self._location(context) in self.inventory.shelves:
            shelf = self._location(context)  # a retried take forgets where it looked
        if shelf is not None:
            self.inspect(context, shelf, sought=goal, run=run)
        return self.pursue(context, goal, run, take=skill == "pick")

    def pursue(self, context: SkillContext, goal: str, run: StepRunner, *,
               take: bool = True) -> Outcome:
        """Recur diagnosis → decision → plan → execution until ``goal`` is in hand or impossible.

        With ``take`` off (a failed find), the cycle ends when the robot sees the
        product, and offers no alternative.
        """
        wanted, offering = goal, False
        for _turn in range(self.max_turns):
            if take and goal in self._held(context):
                return self._taken(context, wanted, goal, offering, run)
            diagnosis = self._diagnose(context, goal)
            if goal in diagnosis.ran_out or goal not in diagnosis.location:
                self._ran_out(context, goal, diagnosis)
                alternative = self.inventory.substitute(goal)
                if (take and self.offer_alternatives and not offering and alternative is not None
                        and alternative not in self.delivered
                        and not self.inventory.out_of_stock(alternative)):
                    goal, offering = alternative, True
                    continue
                return Outcome.failed(ErrorCode.NOT_FOUND, f"we ran out of {wanted}",
                                      ran_out=wanted)
            decision = self._decide(context, goal, diagnosis)
            if decision is None:
                self.records.append(CycleRecord(goal, diagnosis, None, "failed"))
                return Outcome.failed(ErrorCode.NO_PATH, f"I cannot plan how to get the {goal}")
            ended = self._execute(context, decision.plan, goal, take, run)
            self.records.append(CycleRecord(goal, diagnosis, decision,
                                            "surprise" if ended is None else (
                                                "taken" if ended else "failed")))
            if ended is None:
                continue
            if not ended or not take:
                return ended
            return self._taken(context, wanted, goal, offering, run)
        return Outcome.failed(ErrorCode.NOT_FOUND, f"I gave up looking for the {wanted}")

    # -- observing -----------------------------------------------------------------------------

    def inspect(self, context: SkillContext, shelf: str, sought: str | None = None, *,
                run: StepRunner) -> Observation | None:
        """Look at a shelf (driving there), then fulfil the cognitive obligations it raises.

        ``run`` runs the look (the executive's ``run_step``, or the runner a protocol gets).
        """
        place = self.inventory.place(shelf)
        looked = run("look", {"placement": place}, recover=False)
        if not looked:
            return None
        labels = set(looked.data["objects"])
        if sought is not None and sought not in labels:
            # A missed detection rarely repeats: look once more before believing the absence.
            again = run("look", {"placement": place}, recover=False)
            labels |= set(again.data.get("objects", ()))
        observation = observe(self.inventory, shelf, sorted(labels), context.robot.now())
        if sought is not None and sought not in observation.seen:
            seen = listing(sorted(observation.seen))
            speak(context, f"I see {seen}, but I do not see the {sought}." if seen
                  else f"I do not see the {sought}.")
        notes = fulfil_cognitive_obligations(self.inventory, observation)
        for change in notes.said:
            speak(context, change)
            context.events.record("kb.update", text=change)
        self.previous_shelves[shelf] = set(observation.seen)
        for product, obligation in list(self.pending.items()):
            gone = obligation.source == shelf and product not in observation.seen
            if gone or (product in observation.seen and self.inventory.of_class(product, shelf)):
                del self.pending[product]
        for obligation in notes.obligations:
            self.pending[obligation.product] = obligation
        return observation

    # -- the three inferences ------------------------------------------------------------------

    def _diagnose(self, context: SkillContext, goal: str) -> Diagnosis:
        held = self._held(context)
        diagnosis = diagnose(self.inventory, self.previous_shelves, self._here(context),
                             self._distance(context), sought=goal,
                             carried={*held, *self.delivered}, robot_moved=self.robot_moved,
                             previous=self.diagnosis, rng=self.rng)
        self.diagnosis = diagnosis
        context.events.record("inference.diagnosis", goal=goal,
                              assumed={p: diagnosis.location[p] for p in diagnosis.assumed},
                              ran_out=sorted(diagnosis.ran_out),
                              assistant=[list(a) for a in diagnosis.actions])
        for product in sorted(diagnosis.revised & {goal}):
            speak(context, f"I was wrong about the {product}; {_pronoun(product)} must be on "
                           f"{self.inventory.shelf_name(diagnosis.location[product])}.")
        if goal in diagnosis.assumed and goal not in diagnosis.revised:
            speak(context, f"The {goal} must have been placed on "
                           f"{self.inventory.shelf_name(diagnosis.location[goal])}.")
        return diagnosis

    def _decide(self, context: SkillContext, goal: str, diagnosis: Diagnosis) -> Decision | None:
        held = self._held(context)
        request = Carry(goal, HAND if goal in held else diagnosis.location[goal], USER,
                        assumed=goal in diagnosis.assumed)
        pending = []
        for product, obligation in sorted(self.pending.items()):
            if product == goal:
                continue
            source = HAND if product in held else diagnosis.location.get(product)
            if source is not None:
                pending.append(Carry(product, source, obligation.destination,
                                     assumed=product in diagnosis.assumed))
        decision = decide(request, pending, self._location(context), self._distance(context),
                          r_max=self.r_max, holding=held, hands=len(context.robot.hands),
                          model=self.model, rewards=self.rewards)
        if decision is not None:
            context.events.record("inference.decision", goal=goal,
                                  chosen=[c.product for c in decision.chosen],
                                  plan=[str(a) for a in decision.plan.actions],
                                  cost=round(decision.plan.cost, 1),
                                  within_budget=decision.within_budget)
            extra = [c.product for c in decision.put_backs]
            if extra:
                speak(context, f"I will bring the {goal} and put {listing(extra, 'the ')} "
                               "back on the way.")
        return decision

    # -- execution -----------------------------------------------------------------------------

    def _execute(self, context: SkillContext, plan: Plan, goal: str, take: bool,
                 run: StepRunner) -> Outcome | None:
        """Run the plan up to going to the client: the outcome of taking ``goal``, or None.

        None means the world surprised the robot (a look or a take refuted the
        diagnosis): the cycle recurs. Going to the client and handing over are the
        executive's next steps; put-backs planned after them wait for idle time.
        """
        taken: Outcome | None = None
        for action in plan.actions:
            if action.kind == "search_user" or (action.kind == "deliver" and action.where == USER):
                break
            if action.kind == "move":
                moved = run("navigate", {"to": self.inventory.place(action.where)},
                            recover=False)
                if not moved:
                    return moved
            elif action.kind == "search":
                observation = self.inspect(context, action.where, sought=action.product,
                                           run=run)
                if observation is None or action.product not in observation.seen:
                    return None
            elif action.kind == "take" and action.product == goal and not take:
                return self._see(context, action.where, goal, run)
            elif action.kind == "take":
                outcome = self._take(context, action, run)
                if action.product == goal:
                    if outcome is None or not outcome:
                        return outcome
                    taken = outcome
                elif outcome is None or not outcome:
                    return None  # a put-back that could not be taken: decide again
            elif not self._put_back(context, action, run):
                return None
        return taken

    def _see(self, context: SkillContext, shelf: str, goal: str,
             run: StepRunner) -> Outcome | None:
        """A find's end: the product seen on the shelf (None: it is not there)."""
        observation = self.inspect(context, shelf, sought=goal, run=run)
        if observation is None or goal not in observation.seen:
            return None
        place = self.inventory.place(shelf)
        return Outcome.verified(f"I see the {goal} on the {place}", object=goal, placement=place)

    def _take(self, context: SkillContext, action: BasicAction,
              run: StepRunner) -> Outcome | None:
        product, shelf = action.product, action.where
        place = self.inventory.place(shelf)
        context.bindings[f"placement:{product}"] = place
        taken = run("pick", {"object": product}, recover=False)
        if taken:
            self.robot_moved.setdefault(product, shelf)
            self.previous_shelves.get(shelf, set()).discard(product)
            self.inventory.believe_at(product, ROBOT, "")
            speak(context, f"I took the {product}.")
            return taken
        if taken.error is ErrorCode.NOT_FOUND:
            self.inspect(context, shelf, sought=product, run=run)
            return None
        return taken

    def _put_back(self, context: SkillContext, action: BasicAction, run: StepRunner) -> bool:
        product, shelf = action.product, action.where
        placed = run("place", {"placement": self.inventory.place(shelf), "object": product},
                     recover=False)
        if not placed:
            return False
        self.objects_placed.append(product)
        self.pending.pop(product, None)
        text = f"I put the {product} back on {self.inventory.shelf_name(shelf)}."
        self.inventory.believe_home(product, text)
        speak(context, text)
        if shelf in self.previous_shelves:
            self.previous_shelves[shelf].add(product)
        else:
            self.inspect(context, shelf, run=run)  # standing there anyway: see the whole shelf
        return True

    def _ran_out(self, context: SkillContext, goal: str, diagnosis: Diagnosis) -> None:
        self.records.append(CycleRecord(goal, diagnosis, None, "ran_out"))
        if self.inventory.out_of_stock(goal):
            speak(context, f"We ran out of {goal}.")  # known already: the manager knows too
            return
        text = f"We ran out of {goal}."
        self.inventory.believe_out_of_stock(goal, text)
        speak(context, f"I have looked on every shelf: {text[0].lower()}{text[1:]}")
        home = self.inventory.home(goal)
        where = self.inventory.shelf_name(home) if home else "its shelf"
        message = f"Inventory: {goal} is out of stock on {where}."
        misplaced = sorted(self.pending)
        if misplaced:
            message += f" Misplaced: {', '.join(misplaced)}."
        self.messages.append(message)
        context.events.record("message", to="manager", text=message)

    def _taken(self, context: SkillContext, wanted: str, goal: str, offering: bool,
               run: StepRunner) -> Outcome:
        hand = context.beliefs.hand_holding(goal)
        taken = Outcome.verified(f"I have the {goal}", object=goal, hand=hand)
        if not offering:
            return taken
        run("navigate", {"to": self.client})
        question = f"We ran out of {wanted}. Would you like {goal} instead?"
        answer = run("ask", {"question": question, "person": self.client}, recover=False)
        words = str(answer.data.get("answer", "")).lower()
        if answer and words.startswith(_YES):
            context.bindings[f"object:{wanted}"] = goal
            return taken
        speak(context, f"All right, I will put the {goal} back.")
        home = self.inventory.home(goal)
        if home is not None:
            run("place", {"placement": self.inventory.place(home), "object": goal},
                recover=False)
        return Outcome.failed(ErrorCode.NOT_FOUND, f"we ran out of {wanted}", ran_out=wanted)

    # -- after the request ---------------------------------------------------------------------

    def handed_over(self, product: str) -> None:
        """The client took ``product``: the KB places it with them."""
        self.delivered.add(product)
        self.pending.pop(product, None)
        self.inventory.believe_at(product, CUSTOMER, f"The {product} went to the client.")

    def tidy_up(self, context: SkillContext, budget: float | None = None, *,
                run: StepRunner) -> list[str]:
        """Idle time: put back what is in hand, and the misplaced products cheap to put back.

        Returns the products put back. ``budget`` (seconds, default ``r_max``) bounds
        the plan for the pending obligations not already in hand; ``run`` runs the
        steps (the executive's ``run_step``).
        """
        held = self._held(context)
        placed: list[str] = []
        diagnosis = self._diagnose(context, "") if self.pending or held else None
        if diagnosis is None:
            return placed
        carries = []
        for product in sorted({*self.pending, *held}):
            home = self.inventory.home(product)
            source = HAND if product in held else diagnosis.location.get(product)
            if home is not None and source is not None and source != home:
                carries.append(Carry(product, source, home))
        decision = decide(None, carries, self._location(context), self._distance(context),
                          r_max=self.r_max if budget is None else budget, holding=held,
                          hands=len(context.robot.hands), model=self.model,
                          rewards=self.rewards)
        if decision is None:
            return placed
        for action in decision.plan.actions:
            if action.kind == "move":
                if not run("navigate", {"to": self.inventory.place(action.where)},
                           recover=False):
                    break
            elif action.kind == "take":
                if not self._take(context, action, run):
                    break
            elif action.kind == "deliver" and self._put_back(context, action, run):
                placed.append(action.product)
        return placed

    def report_to_manager(self, context: SkillContext) -> str:
        """Text the manager the state of the inventory: what ran out, was put back, is astray."""
        out = sorted(p for p in self.inventory.products if self.inventory.out_of_stock(p))
        astray = sorted(self.pending)
        parts = [f"out of stock: {', '.join(out) or 'nothing'}",
                 f"put back: {', '.join(self.objects_placed) or 'nothing'}",
                 f"still misplaced: {', '.join(astray) or 'nothing'}"]
        message = "Inventory report: " + "; ".join(parts) + "."
        self.messages.append(message)
        context.events.record("message", to="manager", text=message)
        return message

    # -- geometry ------------------------------------------------------------------------------

    def _held(self, context: SkillContext) -> list[str]:
        return sorted(p for p in context.beliefs.holding.values() if p)

    def _here(self, context: SkillContext) -> str | None:
        """The shelf the robot stands at, or the nearest shelf."""
        distance = self._distance(context)
        return min(self.inventory.shelves, key=lambda s: distance(_ROBOT, s), default=None)

    def _location(self, context: SkillContext) -> str:
        """The robot's location as the planner names it: a shelf, the client, or itself."""
        for shelf in self.inventory.shelves:
            pose = resolve_target(context, self.inventory.place(shelf))
            if pose is not None and near(context, pose):
                return shelf
        return _ROBOT

    def _distance(self, context: SkillContext) -> Callable[[str, str], float]:
        points: dict[str, tuple[float, float]] = {_ROBOT: context.robot.pose().xy()}
        for shelf in self.inventory.shelves:
            pose = resolve_target(context, self.inventory.place(shelf))
            if pose is not None:
                points[shelf] = pose.xy()
        client = resolve_target(context, self.client)
        if client is not None:
            points[USER] = client.xy()
        closed = frozenset(context.beliefs.closed_doors)
        cache: dict[tuple[str, str], float] = {}

        def distance(a: str, b: str) -> float:
            if a == b:
                return 0.0
            if (a, b) not in cache:
                if a not in points or b not in points:
                    return float("inf")
                cache[(a, b)] = cache[(b, a)] = context.navigator.distance(
                    points[a], points[b], closed)
            return cache[(a, b)]
        return distance


def _pronoun(product: str) -> str:
    return "they" if product.endswith("s") else "it"


def _model_from(inventory: Inventory) -> ActionModel:
    """The action model from the KB's behaviours (falling back to the defaults)."""
    defaults = ActionModel()
    return ActionModel(
        speed=inventory.behaviour("move", "speed", defaults.speed),
        turn=inventory.behaviour("move", "turn", defaults.turn),
        take_time=inventory.behaviour("take", "time", defaults.take_time),
        deliver_time=inventory.behaviour("deliver", "time", defaults.deliver_time),
        search_time=inventory.behaviour("search", "time", defaults.search_time),
        move_success=inventory.behaviour("move", "success", defaults.move_success),
        take_success=inventory.behaviour("take", "success", defaults.take_success),
        deliver_success=inventory.behaviour("deliver", "success", defaults.deliver_success),
        search_success=inventory.behaviour("search", "success", defaults.search_success))
