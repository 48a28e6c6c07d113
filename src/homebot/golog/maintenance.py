"""Self-maintenance (CAESAR §3.2): the management action theory, Allen constraints, δ → δ′.

The robot's own components (localisation, collision avoidance, laser, camera,
arm controller, speech: *modules* with the states off, starting, running and
failed; the arm: a *posture* such as parked or unparked) form a second basic
action theory, the management BAT: fluent ``component(c)`` and actions
``start(c)``, ``stop(c)``, ``restart(c)``, ``set_posture(c, v)``, each with a
duration. Constraints link task actions to component states in Allen's interval
algebra ("goto_place during collision_avoidance=running"); each task action and
each ``component=state`` is an interval. Before every task action the
constraint network for that action is made path consistent (``homebot.golog.allen``),
which also derives what the constraints imply only together (the laser must run
while driving because collision avoidance must, and collision avoidance runs
during the laser). The relation that remains between the action and each state
says what must hold when the action starts, what must hold (or not) throughout
it (a *marker* the executor watches), and what must begin after it (a
*commitment* on the todo list). The program is transformed: δ = a; δ_rest
becomes δ′ = m1; ...; mk; a; δ_rest with the maintenance actions m_i that bring
the components into those states, in an order the constraints between states
allow. A marker that fires (a crash) interrupts the action; the crashed module
is restarted and the action is done again. A restart that keeps failing is
reported to the operator with the component's name.

Constraints come from a YAML ``maintenance`` section of a world or robot file.
"""

from __future__ import annotations

import re
from abc import abstractmethod
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator

from homebot.errors import GologError
from homebot.golog.allen import (
    ALL,
    DISJOINT,
    NAMES,
    WITHIN,
    Constraint,
    Network,
    conflicting,
    mask_of,
    network_of,
)
from homebot.golog.expressions import Const, Expr, Fn
from homebot.golog.interpreter import (
    Executor,
    Interpreter,
    ProgramTrace,
    Report,
    SimulatedExecutor,
)
from homebot.golog.program import Call, Program, Seq
from homebot.golog.semantics import ActionStep
from homebot.golog.theory import GroundAction, State, Theory, action_text
from homebot.yamlfile import (
    LocatedDocument,
    field_error,
    load_yaml_document,
    parse_yaml_text,
    short_repr,
)

__all__ = [
    "BEGINS_AFTER",
    "COVERS_START",
    "ENDED_BEFORE",
    "MANAGEMENT_ACTIONS",
    "MODULE_STATES",
    "Commitment",
    "Component",
    "Maintenance",
    "MaintenanceExecutor",
    "MaintenanceInterpreter",
    "ProjectionExecutor",
    "Requirements",
    "Transformation",
    "add_management",
    "load_maintenance",
    "maintenance_from_text",
    "parse_constraint",
]

MODULE_STATES = ("off", "starting", "running", "failed")
MANAGEMENT_ACTIONS = ("start", "stop", "restart", "set_posture")
#: relations under which the state holds at the moment the action starts
COVERS_START = mask_of("starts", "started-by", "during", "finishes", "overlapped-by", "equals")
#: relations under which the state begins only after the action ends
BEGINS_AFTER = mask_of("before", "meets")
#: relations under which the state ended before the action starts
ENDED_BEFORE = mask_of("after", "met-by")
#: relations under which the interval begins no earlier than the other
NOT_EARLIER = mask_of("starts", "during", "finishes", "equals", "started-by", "overlapped-by",
                      "met-by", "after")
#: named relation sets a constraint may use besides the 13 basic relations
SHORTHANDS = {"disjoint": DISJOINT, "within": WITHIN}

#### the file


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class ComponentModel(_Strict):
    """One component in the ``maintenance`` section."""

    name: str = Field(pattern=r"^[a-z][a-z0-9_]*$", description="a lower-case identifier")
    kind: Literal["module", "posture"] = "module"
    states: list[str] | None = Field(default=None, min_length=2,
                                     description="a posture's states, e.g. [parked, unparked]")
    initial: str | None = None
    start: float = Field(default=1.0, gt=0, description="seconds a start takes")
    stop: float = Field(default=0.5, gt=0, description="seconds a stop takes")
    restart: float = Field(default=2.0, gt=0, description="seconds a restart takes")
    move: float = Field(default=2.0, gt=0, description="seconds a posture change takes")

    @field_validator("initial", "states", mode="before")
    @classmethod
    def _yaml_booleans(cls, value: Any) -> Any:
        """YAML 1.1 reads a bare ``off`` / ``on`` as a boolean: read it back as the word."""
        def word(item: Any) -> Any:
            return {False: "off", True: "on"}.get(item, item) if isinstance(item, bool) else item

        return [word(item) for item in value] if isinstance(value, list) else word(value)


class MaintenanceModel(_Strict):
    """The ``maintenance`` section: components, constraints and how often to restart."""

    components: list[ComponentModel] = Field(min_length=1)
    constraints: list[str] = Field(default_factory=list)
    restart_attempts: int = Field(default=3, ge=1, le=20,
                                  description="restarts tried before the operator is told")
    retries: int = Field(default=5, ge=0, le=50,
                         description="times an interrupted action is done again")


class _File(BaseModel):
    model_config = ConfigDict(extra="allow")

    maintenance: MaintenanceModel


@dataclass(frozen=True)
class Component:
    """A component: its kind, states, initial state and the durations of its actions."""

    name: str
    kind: str
    states: tuple[str, ...]
    initial: str
    durations: Mapping[str, float]

    @property
    def targets(self) -> tuple[str, ...]:
        """States maintenance can bring it into, most preferred first."""
        return ("running", "off") if self.kind == "module" else self.states


_TERM = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:=([A-Za-z_][A-Za-z0-9_]*))?$")


def parse_constraint(text: str, place: str = "") -> Constraint:
    """``SUBJECT RELATION[|RELATION...] OBJECT``; a term is an action name or ``component=state``.

    Relations are Allen's 13 (before, meets, overlaps, starts, during, finishes,
    equals, and their converses after, met-by, overlapped-by, started-by,
    contains, finished-by) or the shorthands ``disjoint`` and ``within``.
    """
    parts = text.split()
    if len(parts) != 3:
        raise GologError(f"{place}: '{text}': a constraint is 'SUBJECT RELATION OBJECT', e.g. "
                         "'goto_place during collision_avoidance=running'")
    subject, relation, obj = parts
    mask = 0
    for name in relation.split("|"):
        if name in SHORTHANDS:
            mask |= SHORTHANDS[name]
        elif name in NAMES:
            mask |= mask_of(name)
        else:
            raise GologError(f"{place}: '{text}': '{name}' is not an Allen relation; use one "
                             f"of {', '.join(NAMES)}, disjoint or within (join with '|')")
    for term in (subject, obj):
        if not _TERM.match(term):
            raise GologError(f"{place}: '{text}': '{term}' is neither an action name nor "
                             "'component=state'")
    if subject == obj:
        raise GologError(f"{place}: '{text}': a constraint relates two different intervals")
    return Constraint(subject, mask, obj, text, place)


def load_maintenance(path: str | Path) -> Maintenance:
    """The ``maintenance`` section of a world or robot YAML file, validated.

    Raises ``WorldError`` for a malformed section (file, line and field) and
    ``GologError`` for a bad constraint or an inconsistent set (naming the
    constraints that conflict).
    """
    return _from_document(load_yaml_document(path, GologError))


def maintenance_from_text(text: str, source: str = "<text>") -> Maintenance:
    """Like ``load_maintenance``, from YAML text."""
    return _from_document(parse_yaml_text(text, source, GologError))


def _from_document(document: LocatedDocument) -> Maintenance:
    data = document.data
    if not isinstance(data, dict) or "maintenance" not in data:
        raise GologError(f"{document.source}: line 1: no 'maintenance' section; add one with "
                         "'components' and 'constraints'")
    try:
        model = _File.model_validate(data).maintenance
    except ValidationError as error:
        detail = error.errors()[0]
        location = list(detail["loc"])
        kind = detail["type"]
        if kind == "extra_forbidden":
            message = "unknown field; fields are " + ", ".join(
                ComponentModel.model_fields if "components" in location
                else MaintenanceModel.model_fields)
        elif kind == "missing":
            message = "required field is missing; add it"
        else:
            message = (str(detail["msg"]).replace("Input should be", "must be", 1)
                       + f" (got {short_repr(detail.get('input'))})")
        raise GologError(field_error(document, location, message)) from None
    components: dict[str, Component] = {}
    for index, item in enumerate(model.components):
        where: list[str | int] = ["maintenance", "components", index]
        if item.name in components:
            raise GologError(field_error(document, [*where, "name"],
                                         f"'{item.name}' is declared twice; keep one"))
        states = MODULE_STATES if item.kind == "module" else tuple(item.states or ())
        if item.kind == "posture" and not item.states:
            raise GologError(field_error(document, where, "a posture needs 'states', e.g. "
                                         "[parked, unparked]"))
        if item.kind == "module" and item.states is not None:
            raise GologError(field_error(document, [*where, "states"], "a module's states are "
                                         "always off, starting, running, failed; remove it"))
        initial = item.initial if item.initial is not None else states[0]
        allowed = ("off", "running") if item.kind == "module" else states
        if initial not in allowed:
            raise GologError(field_error(document, [*where, "initial"],
                                         f"'{initial}' is not a state it can start in; use one "
                                         f"of {', '.join(allowed)}"))
        components[item.name] = Component(item.name, item.kind, states, initial,
                                          {"start": item.start, "stop": item.stop,
                                           "restart": item.restart, "set_posture": item.move})
    constraints = []
    for index, text in enumerate(model.constraints):
        spot: list[str | int] = ["maintenance", "constraints", index]
        place = f"{document.source}:{document.line_of(spot)}"
        constraint = parse_constraint(text, place)
        for term in (constraint.subject, constraint.object):
            if "=" in term:
                name, state = term.split("=")
                if name not in components:
                    raise GologError(f"{place}: '{text}': no component '{name}'; declared: "
                                     f"{', '.join(components)}")
                if state not in components[name].states:
                    raise GologError(f"{place}: '{text}': '{state}' is not a state of "
                                     f"{name} ({', '.join(components[name].states)})")
        constraints.append(constraint)
    return Maintenance(components, constraints, restart_attempts=model.restart_attempts,
                       retries=model.retries, source=document.source)


#### the constraints, solved per action


@dataclass(frozen=True)
class Commitment:
    """An entry of the todo list: ``component`` must (or must not) be ``state``.

    ``kind`` is ``throughout`` (a marker: for as long as ``action`` runs),
    ``after`` (must begin once ``action`` has ended) or ``before`` (must have
    held, and ended, before ``action`` starts).
    """

    kind: str
    component: str
    state: str
    action: str
    holds: bool = True

    def __str__(self) -> str:
        sign = "=" if self.holds else "≠"
        return {"throughout": f"{self.component}{sign}{self.state} while {self.action}",
                "after": f"{self.component}={self.state} after {self.action}",
                "before": f"{self.component}={self.state} once before {self.action}",
                }[self.kind]


@dataclass(frozen=True)
class Requirements:
    """What the constraints demand of the components for one task action."""

    action: str
    must: Mapping[str, str]  #: component -> state it must be in when the action starts
    must_not: Mapping[str, frozenset[str]]  #: component -> states it must not be in then
    markers: tuple[Commitment, ...]
    after: tuple[Commitment, ...]
    before: tuple[Commitment, ...]
    relations: Mapping[str, int] = field(default_factory=dict)  #: state term -> relation set

    @property
    def empty(self) -> bool:
        return not (self.must or self.must_not or self.after or self.before)


class Maintenance:
    """Components and constraints; solves and caches each task action's requirements."""

    def __init__(self, components: Mapping[str, Component], constraints: Sequence[Constraint],
                 *, restart_attempts: int = 3, retries: int = 5, source: str = "",
                 check: bool = True) -> None:
        self.components = dict(components)
        self.constraints = list(constraints)
        self.restart_attempts = restart_attempts
        self.retries = retries
        self.source = source
        self.states = [f"{name}={state}" for name, component in self.components.items()
                       for state in component.states]
        self.background = [
            Constraint(f"{name}={first}", DISJOINT, f"{name}={second}",
                       f"{name}={first} disjoint {name}={second}", "a component is in one state")
            for name, component in self.components.items()
            for i, first in enumerate(component.states) for second in component.states[i + 1:]]
        self._cache: dict[str, Requirements] = {}
        self._base: Network | None = None
        if check:
            self.check()

    @property
    def actions(self) -> set[str]:
        """The task action names the constraints mention."""
        return {term for constraint in self.constraints
                for term in (constraint.subject, constraint.object) if "=" not in term}

    def check(self, theory: Theory | None = None) -> None:
        """Raise ``GologError`` naming the constraints that conflict, or an unknown action."""
        if theory is not None:
            for constraint in self.constraints:
                for term in (constraint.subject, constraint.object):
                    if "=" not in term and term not in theory.actions:
                        raise GologError(
                            f"{constraint.place}: '{constraint.text}': '{term}' is not an "
                            f"action of the theory '{theory.name}'; actions: "
                            f"{', '.join(sorted(theory.actions))}")
        conflict = conflicting(self.constraints, self.background)
        if conflict:
            raise GologError(f"{self.source}: the maintenance constraints cannot all hold; "
                             "these conflict: " + "; ".join(str(c) for c in conflict)
                             + ". Remove or weaken one of them")

    def forget(self) -> None:
        """Drop every solved network (the next action is solved from scratch)."""
        self._base = None
        self._cache.clear()

    def base_network(self) -> Network:
        """The states and the constraints between them, path consistent (solved once)."""
        if self._base is None:
            between_states = [c for c in self.constraints
                              if "=" in c.subject and "=" in c.object]
            network = network_of([*self.background, *between_states], self.states)
            if network is None or not network.path_consistency():
                raise GologError(f"{self.source}: the constraints between component states "
                                 "cannot all hold; run 'homebot golog maintain' to see which")
            self._base = network
        return self._base

    def solve(self, action: str) -> Network:
        """The path-consistent network of the states with ``action`` (no caching)."""
        network = self.base_network().copy()
        index = network.add(action)
        for constraint in self.constraints:
            if constraint.subject == action and "=" in constraint.object:
                network.restrict(action, constraint.relations, constraint.object)
            elif constraint.object == action and "=" in constraint.subject:
                network.restrict(constraint.subject, constraint.relations, action)
        changed = [(min(index, other), max(index, other)) for other in range(index)
                   if network.relations[index][other] != ALL]
        if not network.path_consistency(changed):
            raise GologError(f"{self.source}: the constraints on '{action}' cannot all hold")
        return network

    def requirements(self, action: str, *, cached: bool = True) -> Requirements:
        """What must hold before, during and after ``action`` (solved once per action name)."""
        if cached and action in self._cache:
            return self._cache[action]
        network = self.solve(action)
        must: dict[str, str] = {}
        must_not: dict[str, set[str]] = {}
        markers, after, before = [], [], []
        relations = {}
        for term in self.states:
            relation = network.relation(action, term)
            if relation == ALL:
                continue
            relations[term] = relation
            component, state = term.split("=")
            if relation & ~COVERS_START == 0:
                must[component] = state
                if relation & ~WITHIN == 0:
                    markers.append(Commitment("throughout", component, state, action))
            elif relation & COVERS_START == 0 and not _one_sided(relation):
                must_not.setdefault(component, set()).add(state)
                if relation & ~DISJOINT == 0:
                    markers.append(Commitment("throughout", component, state, action, False))
            if relation & ~BEGINS_AFTER == 0:
                after.append(Commitment("after", component, state, action))
            elif relation & ~ENDED_BEFORE == 0:
                before.append(Commitment("before", component, state, action))
        # a state that must hold excludes the component's other states anyway
        for component in must:
            must_not.pop(component, None)
        markers = [m for m in markers if m.holds or m.component not in must]
        found = Requirements(action, must, {c: frozenset(s) for c, s in must_not.items()},
                             tuple(markers), tuple(after), tuple(before), relations)
        if cached:
            self._cache[action] = found
        return found

    def target(self, component: str, current: str, requirements: Requirements) -> str | None:
        """The state ``component`` must be brought into before the action, if it must change."""
        if component in requirements.must:
            wanted = requirements.must[component]
            return None if wanted == current else wanted
        excluded = requirements.must_not.get(component, frozenset())
        if current not in excluded and current not in ("starting", "failed"):
            return None
        if current not in excluded:  # starting or failed, and neither excluded: leave it
            return None
        for state in self.components[component].targets:
            if state not in excluded:
                return state
        raise GologError(f"{self.source}: no state of {component} is allowed while "
                         f"{requirements.action} runs")

    def order(self, changes: Mapping[str, str]) -> list[str]:
        """Components to change, each after those whose new state must begin earlier."""
        base = self.base_network()
        pending = sorted(changes)
        ordered: list[str] = []
        while pending:
            for component in pending:
                term = f"{component}={changes[component]}"
                waits = any(base.relation(term, f"{other}={changes[other]}") & ~NOT_EARLIER == 0
                            for other in pending if other != component)
                if not waits:
                    break
            else:
                component = pending[0]
            pending.remove(component)
            ordered.append(component)
        return ordered

    def actions_for(self, component: str, current: str, target: str) -> list[GroundAction]:
        """The management actions that take ``component`` from ``current`` to ``target``."""
        if self.components[component].kind == "posture":
            return [("set_posture", component, target)]
        if target == "running":
            return [("start", component)] if current == "off" else [("restart", component)]
        return [("stop", component)]

    def plan(self, states: Mapping[str, str], requirements: Requirements,
             seen: Iterable[str] = ()) -> list[GroundAction]:
        """δ′'s prefix: management actions that make ``requirements`` hold from ``states``."""
        changes: dict[str, str] = {}
        for name in self.components:
            wanted = self.target(name, states[name], requirements)
            if wanted is not None:
                changes[name] = wanted
        prefix: list[GroundAction] = []
        earlier = set(seen)
        for commitment in requirements.before:
            # the state must have held and ended: go through it, or end it if it holds now
            name, state = commitment.component, commitment.state
            if name in changes or (f"{name}={state}" in earlier and states[name] != state):
                continue
            if states[name] != state:
                prefix += self.actions_for(name, states[name], state)
                states = {**states, name: state}
            changes[name] = next(s for s in self.components[name].targets if s != state)
        for name in self.order(changes):
            prefix += self.actions_for(name, states[name], changes[name])
        return prefix


def _one_sided(relation: int) -> bool:
    """Only 'the state begins after' or only 'the state ended before': it speaks of another
    interval of that state than the one (if any) holding when the action starts."""
    return relation & ~BEGINS_AFTER == 0 or relation & ~ENDED_BEFORE == 0


#### the management action theory


def add_management(theory: Theory, maintenance: Maintenance) -> Theory:
    """Add the management BAT to a task theory (in place): fluent ``component(c)``,
    actions ``start(c)``, ``stop(c)``, ``restart(c)``, ``set_posture(c, v)``, exogenous
    ``crash(c)``.

    Preconditions: start needs ``off``; stop needs running, starting or failed; restart
    needs a module; set_posture needs a posture and one of its states.
    Effects: start and restart give ``running``, stop ``off``, crash ``failed``.
    """
    for name in (*MANAGEMENT_ACTIONS, "crash"):
        if name in theory.actions:
            raise GologError(f"the theory '{theory.name}' already has an action '{name}'; "
                             "rename it, the management theory needs that name")
    components = maintenance.components
    theory.fluent("component", 1)
    theory.initially({("component", name): component.initial
                      for name, component in components.items()})

    def module(c: Any) -> bool:
        return c in components and components[c].kind == "module"

    theory.action("start", ("c",),
                  precondition=lambda s, c: module(c) and s.get(("component", c)) == "off",
                  effects=lambda s, c: {("component", c): "running"},
                  description="start a module that is off")
    theory.action("stop", ("c",),
                  precondition=lambda s, c: module(c) and s.get(("component", c)) != "off",
                  effects=lambda s, c: {("component", c): "off"}, description="stop a module")
    theory.action("restart", ("c",), precondition=lambda s, c: module(c),
                  effects=lambda s, c: {("component", c): "running"},
                  description="restart a module (after a crash)")
    theory.action("set_posture", ("c", "v"),
                  precondition=lambda s, c, v: c in components and components[c].kind
                  == "posture" and v in components[c].states,
                  effects=lambda s, c, v: {("component", c): v},
                  description="move a posture component (the arm) into a state")
    theory.action("crash", ("c",), exogenous=True,
                  effects=lambda s, c: {("component", c): "failed"})
    return theory


#### execution: the executor's side, and the interpreter that transforms δ into δ′


class MaintenanceExecutor(Executor):
    """An executor that also reports its components' states (their heartbeats) and
    watches markers while a task action runs.

    When a watched component leaves the state a marker demands, the action is
    interrupted: ``execute`` reports failure and ``interrupted`` names the component.
    """

    interrupted: str | None = None

    @abstractmethod
    def component_states(self) -> dict[str, str]:
        """The state of every component now."""

    def watch(self, markers: Sequence[Commitment]) -> None:
        """Watch these markers during the next task action (none: stop watching)."""


class ProjectionExecutor(MaintenanceExecutor):
    """The robot's own model as the world: components do what they are told, never crash."""

    def __init__(self, theory: Theory, *, seed: int = 0,
                 events: Callable[[int, State], list[GroundAction]] | None = None) -> None:
        self.inner = SimulatedExecutor(theory, seed=seed, events=events)

    def execute(self, action: GroundAction, state: State) -> Report:
        return self.inner.execute(action, state)

    def exogenous(self, state: State) -> list[GroundAction]:
        return self.inner.exogenous(state)

    def wait(self, state: State) -> list[GroundAction] | None:
        return self.inner.wait(state)

    def component_states(self) -> dict[str, str]:
        return {key[1]: value for key, value in self.inner.truth.values.items()
                if key[0] == "component"}


@dataclass
class Transformation:
    """One δ → δ′ step: the action, the maintenance prefix, its markers and the todo list."""

    action: str
    prefix: list[str]
    markers: list[str]
    todo: list[str]
    program: str


class MaintenanceInterpreter(Interpreter):
    """The online interpreter with self-maintenance before each task action.

    The theory must include the management BAT (``add_management``). Log entries
    of kind ``maintenance.*`` record what was noticed, the transformation, the
    repairs, the interruptions and what the operator was told.
    """

    def __init__(self, theory: Theory, executor: MaintenanceExecutor,
                 maintenance: Maintenance, **options: Any) -> None:
        super().__init__(theory, executor, **options)
        self.maintenance = maintenance
        self.components: MaintenanceExecutor = executor
        self.todo: list[Commitment] = []
        self.seen: set[str] = set()
        self.transformations: list[Transformation] = []

    def _run(self, program: Program, run: ProgramTrace) -> str:
        self.todo, self.transformations = [], []
        self.seen = {f"{key[1]}={value}" for key, value in run.state.values.items()
                     if key[0] == "component"}
        failure = super()._run(program, run)
        if not failure and any(c.kind == "after" for c in self.todo):
            run.state, failure = self._discharge(run, run.state)
        return failure

    def _execute(self, run: ProgramTrace, step: ActionStep, state: State,
                 remaining: Program) -> tuple[State, Program, str]:
        name = str(step.action[0])
        if name in MANAGEMENT_ACTIONS:
            return super()._execute(run, step, state, remaining)
        requirements = self.maintenance.requirements(name)
        rest, failure = remaining, ""
        for _ in range(self.maintenance.retries + 1):
            state, failure = self._prepare(run, step.action, requirements, state, remaining)
            if failure:
                return state, remaining, failure
            self.components.interrupted = None
            self.components.watch(requirements.markers)
            state, rest, failure = super()._execute(run, step, state, remaining)
            self.components.watch(())
            self.todo = [c for c in self.todo if c.kind != "throughout"]
            crashed = self.components.interrupted
            if not failure or crashed is None:
                break
            self._log(run, {"kind": "maintenance.interrupted", "action": action_text(step.action),
                            "component": crashed})
        else:
            return state, rest, failure
        if failure:
            return state, rest, failure
        self.todo += list(requirements.after)
        state, failure = self._discharge(run, state)
        return state, rest, failure

    def _sync(self, run: ProgramTrace, state: State) -> tuple[State, dict[str, str]]:
        """Read the components' heartbeats; note what changed unseen (a crash)."""
        states = self.components.component_states()
        changed = {}
        for component, value in states.items():
            if state.get(("component", component)) != value:
                changed[("component", component)] = value
                self._log(run, {"kind": "maintenance.noticed", "component": component,
                                "state": value})
        self.seen |= {f"{c}={v}" for c, v in states.items()}
        return (state.progressed(changed) if changed else state), states

    def _prepare(self, run: ProgramTrace, action: GroundAction, requirements: Requirements,
                 state: State, remaining: Program) -> tuple[State, str]:
        """Transform and run δ′'s prefix until the requirements hold (or repair fails)."""
        attempts: dict[str, int] = {}
        for attempt in range(4 * len(self.maintenance.components) + 4):
            state, states = self._sync(run, state)
            prefix = self.maintenance.plan(states, requirements, self.seen)
            markers = [str(marker) for marker in requirements.markers]
            self.todo = [c for c in self.todo if c.kind != "throughout"] + list(
                requirements.markers)
            if not prefix:
                if attempt == 0:
                    self._record(action, [], markers, remaining)
                return state, ""
            self._record(action, prefix, markers, remaining)
            self._log(run, {"kind": "maintenance.transform", "action": action_text(action),
                            "prefix": [action_text(m) for m in prefix], "markers": markers,
                            "todo": [str(c) for c in self.todo]})
            for management in prefix:
                component = str(management[1])
                report = self.components.execute(management, state)
                self._log(run, {"kind": "action", "action": action_text(management),
                                "ok": report.ok, "message": report.message})
                if not report:
                    attempts[component] = attempts.get(component, 0) + 1
                    if attempts[component] >= self.maintenance.restart_attempts:
                        value = self.components.component_states().get(component, "unknown")
                        return state, self._tell_operator(run, component, value)
                    break
                run.history.append(management)
                state = self.theory.do(management, state)
        return state, self._tell_operator(run, "", "")

    def _discharge(self, run: ProgramTrace, state: State) -> tuple[State, str]:
        """Make the 'after' commitments on the todo list hold now."""
        pending = [c for c in self.todo if c.kind == "after"]
        if not pending:
            return state, ""
        requirements = Requirements("(todo)", {c.component: c.state for c in pending}, {},
                                    (), (), ())
        state, failure = self._prepare(run, ("(todo)",), requirements, state, Seq(()))
        if not failure:
            self.todo = [c for c in self.todo if c.kind != "after"]
        return state, failure

    def _tell_operator(self, run: ProgramTrace, component: str, value: str) -> str:
        message = (f"my {component} has {value} and does not come back after "
                   f"{self.maintenance.restart_attempts} restart(s); please check it"
                   if component else "my components do not settle into the states my task "
                   "needs; please check them")
        self._log(run, {"kind": "maintenance.operator", "component": component,
                        "message": message})
        return message

    def _record(self, action: GroundAction, prefix: list[GroundAction], markers: list[str],
                remaining: Program) -> None:
        calls = [Call(str(m[0]), tuple(_const(arg) for arg in m[1:])) for m in prefix]
        if action[0] != "(todo)":
            calls.append(Call(str(action[0]), tuple(_const(arg) for arg in action[1:])))
        program = Seq((*calls, remaining)) if remaining != Seq(()) else Seq(tuple(calls))
        self.transformations.append(Transformation(
            action_text(action), [action_text(m) for m in prefix], markers,
            [str(c) for c in self.todo], str(program)))


def _const(value: Any) -> Expr:
    """A name for an identifier (``laser``), a quoted constant for anything else."""
    return Fn(value) if isinstance(value, str) and _TERM.match(value) and "=" not in value \
        else Const(value)
