"""The actor: runs a plan operator by operator through the monitored skills, and replans.

Care-O-bot §4: each operator runs as its skill, whose state machine executes,
monitors and reports ``finished`` / ``verified`` / ``failed`` / ``aborted`` /
``retrying`` (the skill layer logs every one). Retries are per operator, with
counts the user gives (``retries={"!grasp": 3}``). A verified operator's
declared effects are checked against what the robot now believes. When an
operator ends failed or aborted, a door or a person in the way first goes
through the executive's recovery protocols; otherwise (or if they do not help)
the robot replans from what it now believes, at most ``max_replans`` times,
before it gives up and says why. Every operator's skill runs through the
executive's ``run_step``, so the task's time budget holds too: once it is spent
the robot stops, without planning again. The planner model stays apart from
execution: ``!grasp`` is planned, the ``pick`` skill runs it.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from rich.markup import escape

from homebot.events import Event
from homebot.executive import WAY_BLOCKED, Executive, RunReport
from homebot.htn.domain import Domain
from homebot.htn.home import Goal, Names, home_domain, state_from_beliefs
from homebot.htn.logic import term_text
from homebot.htn.planner import Plan, Planner, PlanStep
from homebot.htn.state import Atom, State
from homebot.knowledge import KnowledgeBase
from homebot.skills import ErrorCode, Outcome, Status, speak
from homebot.task import Step

__all__ = ["OPERATOR_SKILLS", "HtnTrace", "OperatorReport", "PlanActor", "step_for"]

# Predicates the actor remembers from verified operators across replanning (no sensor
# shows them: what the robot has told whom).
_MEMORY = frozenset({"told", "reported"})
# Predicates of declared effects the actor checks against the beliefs after an operator.
_CHECKED = frozenset({"holding", "has", "object-at", "door-closed"})


def _announce(what: str, thing: str, who: str) -> Step:
    text = {"bring": f"I will bring the {thing} to {who}.",
            "guide": f"I will take {thing} to the {who}."}.get(what, f"I will {what} {thing}.")
    return Step("say", {"text": text})


def _report(what: str, thing: str, who: str) -> Step:
    text = {"bring": f"I have brought the {thing} to {who}.",
            "guide": f"{thing}, we have arrived at the {who}."}.get(what, f"I did {what}.")
    return Step("say", {"text": text})


#: How each operator of the home domain runs: a function of its arguments (robot first,
#: world names) to the skill step that carries it out.
OPERATOR_SKILLS: Mapping[str, Callable[..., Step]] = {
    "!announce": lambda r, what, thing, who: _announce(what, thing, who),
    "!report": lambda r, what, thing, who: _report(what, thing, who),
    "!move_base": lambda r, source, target: Step("navigate", {"to": target}),
    "!open_door": lambda r, door: Step("open_door", {"door": door}),
    "!find_object": lambda r, o, p: Step("find_object", {"object": o, "placement": p}),
    "!search_object": lambda r, o: Step("find_object", {"object": o}),
    "!grasp": lambda r, o, p: Step("pick", {"object": o}),
    "!find_person": lambda r, who: Step("find_person", {"person": {"name": who}}),
    "!hand_over": lambda r, o, who: Step("give", {"person": who, "object": o}),
    "!guide": lambda r, who, place: Step("guide", {"to": place, "person": who}),
    "!put_down": lambda r, o, p: Step("place", {"placement": p, "object": o}),
}


def _searches_everywhere(step: Step) -> bool:
    return step.skill == "find_object" and "placement" not in step.args


def step_for(step: PlanStep, names: Names) -> Step:
    """The skill step that runs a plan step; an operator no skill runs raises ``PlanningError``."""
    from homebot.errors import PlanningError

    make = OPERATOR_SKILLS.get(step.operator)
    if make is None:
        raise PlanningError(f"no skill runs operator '{step.operator}'; the actor knows "
                            f"{', '.join(OPERATOR_SKILLS)} (plan it with 'homebot plan')")
    try:
        return make(*(names.name(arg) for arg in step.args))
    except TypeError:
        raise PlanningError(f"operator '{step.operator}' has {len(step.args)} arguments, not "
                            "the number its skill needs") from None


@dataclass(frozen=True, slots=True)
class OperatorReport:
    """How one operator ended: its skill's status (§4.1), error, attempts and message."""

    operator: str
    args: tuple[Any, ...]
    skill: str
    status: str
    error: str | None = None
    attempts: int = 1
    message: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"operator": self.operator, "args": list(self.args), "skill": self.skill,
                "status": self.status, "error": self.error, "attempts": self.attempts}


@dataclass
class HtnTrace:
    """What an HTN run adds to its report: the goal, every plan made, every operator run."""

    task: tuple[Any, ...]
    plans: list[Plan] = field(default_factory=list)
    operators: list[OperatorReport] = field(default_factory=list)
    replans: int = 0
    searched: set[str] = field(default_factory=set)  #: objects searched for everywhere in vain
    forgotten: set[str] = field(default_factory=set)  #: objects whose misses were forgotten

    def to_dict(self) -> dict[str, Any]:
        return {"task": [term_text(item) for item in self.task], "replans": self.replans,
                "plans": [plan.to_dicts() for plan in self.plans],
                "operators": [report.to_dict() for report in self.operators]}

    def lines(self) -> list[str]:
        """The goal with its plans and replans, then each operator with its skill's final
        status, error and attempts."""
        task = escape("(" + " ".join(term_text(item) for item in self.task) + ")")
        replans = f", {self.replans} replan{'s' * (self.replans != 1)}" if self.replans else ""
        lines = [f"[bold]{task}[/]: {len(self.plans)} plan{'s' * (len(self.plans) != 1)}"
                 f"{replans}"]
        for report in self.operators:
            colour = "green" if report.status == "verified" else (
                "yellow" if report.status == "finished" else "red")
            tries = f" after {report.attempts} attempts" if report.attempts > 1 else ""
            error = f" ({report.error})" if report.error else ""
            args = " ".join(str(arg) for arg in report.args)
            lines.append(f"  [{colour}]{report.status:9}[/] "
                         f"{escape(f'({report.operator} {args}) -> {report.skill}{error}{tries}')}")
        return lines


class PlanActor:
    """Plans a goal from the robot's beliefs and carries the plan out, replanning within a bound.

    Args:
        executive: runs each operator's skill (its recovery protocols mend a closed door
            or a blocked way first; its time budget bounds the whole goal).
        domain: the HTN domain (the home domain unless given).
        retries: extra attempts per operator name, e.g. ``{"!grasp": 3}``.
        max_replans: how many times to replan after a failed or aborted operator.
        knowledge: a knowledge base saying where objects belong (``loc=>PLACE``).
        planner: bounds for each search (``Planner`` keyword arguments).
    """

    def __init__(self, executive: Executive, domain: Domain | None = None, *,
                 retries: Mapping[str, int] | None = None, max_replans: int = 3,
                 knowledge: KnowledgeBase | None = None, **planner: Any) -> None:
        self.executive = executive
        self.context = executive.context
        self.knowledge = knowledge
        self.domain = domain or home_domain()
        self.planner = Planner(self.domain, **planner)
        self.retries = dict(retries or {})
        self.max_replans = max_replans

    def _state(self, goal: Goal, names: Names, memory: set[Atom]) -> State:
        context = self.context
        state, _ = state_from_beliefs(context.world, context.beliefs,
                                      context.robot.pose().xy(), names,
                                      extra=[*goal.atoms, *memory], knowledge=self.knowledge)
        return state

    def run(self, goal: Goal, names: Names | None = None) -> RunReport[HtnTrace]:
        """Plan, act, monitor, replan; the robot says how it ended."""
        context = self.context
        names = names or Names()
        began = self.executive.begin()
        context.events.record("htn.goal", task=list(goal.task))
        run = HtnTrace(goal.task)
        memory: set[Atom] = set()
        success, reason = False, ""
        while True:
            result = self.planner.search(self._state(goal, names, memory), [goal.task])
            if result.plan is None:
                reason = ("I found no plan from what I now believe"
                          if not result.stopped else f"planning stopped ({result.stopped})")
                break
            plan = result.plan
            for step in plan.steps:  # every operator must have a skill before the robot moves
                if not self.domain.operators[step.operator].internal:
                    step_for(step, names)
            run.plans.append(plan)
            context.events.record("htn.plan", replan=run.replans, plan=plan.to_dicts())
            failure = self._execute(plan, names, memory, goal, run)
            if failure is None:
                success = True
                break
            if run.operators and run.operators[-1].error == ErrorCode.OUT_OF_TIME.value:
                reason = failure  # the budget is spent: no new plan would be carried out
                break
            run.replans += 1
            if run.replans > self.max_replans:
                reason = failure if not self.max_replans else (
                    f"{failure} (and {self.max_replans} new plans did not help)")
                break
            context.events.record("htn.replan", replan=run.replans, reason=failure)
        if success and not any(s.operator == "!report" for s in run.plans[-1].steps):
            speak(context, "I have done what you asked.")
        elif not success:
            speak(context, f"I am sorry, I could not do it: {reason}.")
        context.events.record("htn.end", success=success, replans=run.replans, reason=reason)
        return self.executive.report(began, success, reason, run)

    def _execute(self, plan: Plan, names: Names, memory: set[Atom], goal: Goal,
                 run: HtnTrace) -> str | None:
        """Run the plan's operators in order; the reason of the first failure, or None."""
        for step in plan.steps:
            operator = self.domain.operators[step.operator]
            if operator.internal:
                continue
            skill_step = step_for(step, names)
            outcome, attempts = self._run_operator(step, skill_step, run)
            run.operators.append(OperatorReport(
                step.operator, tuple(names.name(a) for a in step.args), skill_step.skill,
                outcome.status.value, outcome.error.value if outcome.error else None,
                attempts, outcome.message))
            self.context.events.record("htn.operator", operator=step.operator,
                                       args=[names.name(a) for a in step.args],
                                       status=outcome.status.value, attempts=attempts,
                                       error=outcome.error.value if outcome.error else None)
            self._remember(skill_step, outcome, run)
            # finished is as far as a skill goes with monitoring off (a plain sequence)
            if outcome.status not in (Status.VERIFIED, Status.FINISHED):
                return outcome.message or (outcome.error.value if outcome.error else "failed")
            memory.update(atom for atom in step.adds if atom[0] in _MEMORY)
            missing = self._unexpected(list(step.deletes), list(step.adds), goal, names, memory)
            if missing:
                self.context.events.record("htn.effects", operator=step.operator,
                                           missing=missing)
                return f"after {step.operator[1:]} I do not believe {missing[0]}"
        return None

    def _remember(self, skill_step: Step, outcome: Outcome, run: HtnTrace) -> None:
        """What later skills need from this one, as the executive keeps it for GPSR steps.

        A found object's placement is bound for the grasp (a missed second look must
        not make the robot forget where it saw it). A whole-home search that found
        nothing is noted: before searching for it again the robot forgets where it
        did not see the object, since a detection may have missed it.
        """
        context = self.context
        if skill_step.skill == "find_object" and outcome:
            found = outcome.data.get("object")
            context.bindings[f"object:{skill_step.args['object']}"] = found
            context.bindings[f"placement:{found}"] = outcome.data.get("placement")
        if _searches_everywhere(skill_step) and outcome.error is ErrorCode.NOT_FOUND:
            run.searched.add(str(skill_step.args["object"]))

    def _run_operator(self, step: PlanStep, skill_step: Step,
                      run: HtnTrace) -> tuple[Outcome, int]:
        context = self.context
        wanted = str(skill_step.args.get("object"))
        if _searches_everywhere(skill_step) and wanted in run.searched - run.forgotten:
            run.forgotten.add(wanted)
            context.beliefs.not_at.pop(wanted, None)
            context.events.record("belief", what="forgot_not_at", object=wanted)
        retried: list[Event] = []

        def heard(event: Event) -> None:  # heard as recorded: a long run's log lets events go
            if event.kind == "skill.status" and event.data.get("skill") == skill_step.skill \
                    and event.data.get("status") == Status.RETRYING.value:
                retried.append(event)

        context.events.listeners.append(heard)
        try:
            outcome = self.executive.run_step(skill_step.skill, skill_step.args,
                                              recover=WAY_BLOCKED,  # the rest: replan
                                              retries=self.retries.get(step.operator))
        finally:
            context.events.listeners.remove(heard)
        return outcome, 1 + len(retried)

    def _unexpected(self, deletes: list[Atom], adds: list[Atom], goal: Goal, names: Names,
                    memory: set[Atom]) -> list[str]:
        """Declared effects the beliefs do not show (hands ignored: the skill picks the hand)."""
        checked = [atom for atom in (*deletes, *adds) if atom[0] in _CHECKED]
        if not checked:
            return []
        believed = self._state(goal, names, memory)
        held = {atom[2] for atom in believed.atoms("holding")}
        missing = []
        for atom in adds:
            if atom[0] == "holding":
                if atom[2] not in held:
                    missing.append(f"I hold the {names.name(atom[2])}")
            elif atom[0] in _CHECKED and atom not in believed:
                missing.append(" ".join(str(names.name(item)) for item in atom))
        for atom in deletes:
            if atom[0] in _CHECKED - {"holding"} and atom in believed:
                missing.append("not " + " ".join(str(names.name(item)) for item in atom))
        return missing
