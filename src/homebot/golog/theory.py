"""The basic action theory: fluents, primitive and stochastic actions, states by progression.

A state holds the value of every ground fluent that differs from its default,
keyed ``(fluent, *arguments)``. A situation is the initial state with the
history of actions done since; its state is obtained by progression: each
action's effects (the positive and negative effects its successor state axioms
name) replace those fluents' values, and every other fluent keeps its value
(the frame assumption). Ground actions are tuples ``(name, *arguments)``.

Stochastic actions follow DTGolog: the agent's action ``a`` is turned by nature
into one of several deterministic actions ``n_i`` with probability
``prob(n_i, a, s)``; each nature action carries a sensing condition that tells,
after the fact, which one happened.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from homebot.errors import GologError
from homebot.golog.expressions import Const, Expr, as_expr

if TYPE_CHECKING:
    from homebot.golog.program import Procedure

__all__ = [
    "ActionSchema",
    "Fluent",
    "GroundAction",
    "Situation",
    "State",
    "Theory",
    "action_text",
]

GroundAction = tuple[Any, ...]  #: ``(name, *arguments)``
Effects = Callable[..., Mapping[tuple[Any, ...], Any]]
Outcomes = Callable[..., Sequence[tuple[GroundAction, float]]]


def action_text(action: GroundAction) -> str:
    """``name(arg, ...)`` for a ground action."""
    name, *args = action
    return f"{name}({', '.join(map(str, args))})" if args else str(name)


class State:
    """Fluent values in one situation; immutable once built."""

    __slots__ = ("_hash", "values")

    def __init__(self, values: Mapping[tuple[Any, ...], Any] | None = None) -> None:
        self.values: dict[tuple[Any, ...], Any] = dict(values or {})
        self._hash: int | None = None

    def __getitem__(self, key: tuple[Any, ...]) -> Any:
        return self.values.get(key)

    def get(self, key: tuple[Any, ...], default: Any = None) -> Any:
        return self.values.get(key, default)

    def progressed(self, updates: Mapping[tuple[Any, ...], Any]) -> State:
        """A new state: these fluents changed, all others as before."""
        values = dict(self.values)
        values.update(updates)
        return State(values)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, State) and self.values == other.values

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self.values.items()))
        return self._hash

    def __repr__(self) -> str:
        return f"State({self.values!r})"


@dataclass(frozen=True, slots=True)
class Situation:
    """The initial state with the actions done since, and the state they lead to."""

    state: State
    history: tuple[GroundAction, ...] = ()


@dataclass(frozen=True, slots=True)
class Fluent:
    """A relational (``default`` False) or functional fluent with its arity."""

    name: str
    arity: int = 0
    default: Any = None


@dataclass(frozen=True)
class ActionSchema:
    """A primitive action: parameters, precondition axiom, effects, and what kind it is.

    ``precondition`` is a formula over the parameters or ``f(state, *args) -> bool``;
    ``effects(state, *args)`` returns the fluents the action changes and their new
    values. A stochastic action has ``outcomes(state, *args)``: nature's
    deterministic actions with their probabilities. A nature action has a
    ``sense`` condition telling after the fact that it was the one that happened.
    """

    name: str
    parameters: tuple[str, ...] = ()
    precondition: Expr | Callable[..., bool] | None = None
    effects: Effects | None = None
    outcomes: Outcomes | None = None
    sense: Expr | None = None
    exogenous: bool = False
    senses: Callable[..., Iterable[tuple[Any, ...]]] | None = None
    description: str = ""

    @property
    def stochastic(self) -> bool:
        return self.outcomes is not None

    def bind(self, expr: Expr, args: Sequence[Any]) -> Expr:
        return expr.substitute({name: Const(value)
                                for name, value in zip(self.parameters, args, strict=True)})


@dataclass
class Theory:
    """A basic action theory with its initial state and the program's procedures."""

    name: str
    fluents: dict[str, Fluent] = field(default_factory=dict)
    functions: dict[str, Callable[..., Any]] = field(default_factory=dict)
    actions: dict[str, ActionSchema] = field(default_factory=dict)
    procedures: dict[str, Procedure] = field(default_factory=dict)
    initial: State = field(default_factory=State)

    # ------------------------------------------------------------------ declaring

    def fluent(self, name: str, arity: int = 0, default: Any = None, *,
               relational: bool = False) -> Fluent:
        """Declare a fluent; a relational one defaults to False."""
        declared = Fluent(name, arity, False if relational and default is None else default)
        self.fluents[name] = declared
        return declared

    def function(self, name: str, function: Callable[..., Any] | Any) -> None:
        """Declare a defined function ``f(state, *args)`` (or a constant) usable in programs."""
        self.functions[name] = function if callable(function) else (lambda state: function)

    def action(self, name: str, parameters: Sequence[str] = (), *,
               precondition: Expr | Callable[..., bool] | None = None,
               effects: Effects | None = None, sense: Expr | None = None,
               exogenous: bool = False,
               senses: Callable[..., Iterable[tuple[Any, ...]]] | None = None,
               description: str = "") -> ActionSchema:
        """Declare a deterministic primitive (or nature, or exogenous, or sensing) action."""
        schema = ActionSchema(name, tuple(parameters), precondition, effects, None, sense,
                              exogenous, senses, description)
        self.actions[name] = schema
        return schema

    def stochastic(self, name: str, parameters: Sequence[str] = (), *,
                   outcomes: Outcomes, precondition: Expr | Callable[..., bool] | None = None,
                   description: str = "") -> ActionSchema:
        """Declare a stochastic action: ``outcomes(state, *args)`` lists nature's choices."""
        schema = ActionSchema(name, tuple(parameters), precondition, None, outcomes,
                              description=description)
        self.actions[name] = schema
        return schema

    def define(self, *procedures: Procedure) -> None:
        """Add procedures (replacing any of the same name)."""
        for procedure in procedures:
            self.procedures[procedure.name] = procedure

    def initially(self, values: Mapping[tuple[Any, ...], Any]) -> None:
        """Set fluent values of the initial situation."""
        self.initial = self.initial.progressed(values)

    # ------------------------------------------------------------------ reasoning

    def schema(self, action: GroundAction) -> ActionSchema:
        """The schema of a ground action; unknown names or wrong arity raise ``GologError``."""
        schema = self.actions.get(action[0])
        if schema is None:
            raise GologError(f"'{action[0]}' is not an action of the theory '{self.name}'; "
                             f"actions: {', '.join(sorted(self.actions)) or 'none'}")
        if len(action) - 1 != len(schema.parameters):
            raise GologError(f"{action_text(action)}: '{schema.name}' takes "
                             f"{len(schema.parameters)} argument(s) "
                             f"({', '.join(schema.parameters)}), not {len(action) - 1}")
        return schema

    def possible(self, action: GroundAction, state: State) -> bool:
        """``Poss(a, s)``."""
        schema = self.schema(action)
        condition = schema.precondition
        if condition is None:
            return True
        if isinstance(condition, Expr):
            return schema.bind(condition, action[1:]).holds(self, state)
        return bool(condition(state, *action[1:]))

    def do(self, action: GroundAction, state: State) -> State:
        """The state after a deterministic action (progression)."""
        schema = self.schema(action)
        if schema.effects is None:
            return state
        return state.progressed(schema.effects(state, *action[1:]))

    def state_after(self, history: Sequence[GroundAction]) -> State:
        """The state of the situation ``do(history, S0)``: the initial state progressed
        through the history (nature's actions stand for the stochastic ones)."""
        state = self.initial
        for action in history:
            state = self.do(action, state)
        return state

    def outcomes(self, action: GroundAction, state: State) -> list[tuple[GroundAction, float]]:
        """Nature's choices for a stochastic action; a deterministic one has only itself."""
        schema = self.schema(action)
        if schema.outcomes is None:
            return [(action, 1.0)]
        return list(schema.outcomes(state, *action[1:]))

    def sense_condition(self, nature: GroundAction) -> Expr | None:
        """The condition that tells, after the fact, that ``nature`` happened."""
        schema = self.schema(nature)
        return schema.bind(schema.sense, nature[1:]) if schema.sense is not None else None

    def holds(self, condition: Any, state: State) -> bool:
        """Whether a formula holds in ``state``."""
        return as_expr(condition).holds(self, state)

    def value(self, term: Any, state: State) -> Any:
        """The value of a term in ``state``."""
        return as_expr(term).evaluate(self, state)
