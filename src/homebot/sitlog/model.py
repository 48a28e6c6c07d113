"""Situations, dialogue models and programs (§4.1–4.2), built by the loader or in Python."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from homebot.sitlog.terms import Struct, Term, Var, deref

__all__ = [
    "BUILTIN_TYPES",
    "FINAL",
    "INITIAL",
    "RECURSIVE",
    "Arc",
    "DialogueModel",
    "Program",
    "Situation",
    "UserFunction",
    "functor_of",
]

FINAL = "final"  #: a situation that ends its dialogue model
RECURSIVE = "recursive"  #: a situation that runs a whole embedded dialogue model
INITIAL = "is"  #: the id of the initial situation (else the first one listed)
#: Situation types the interpreter handles itself; grounded types go to perception.
BUILTIN_TYPES = frozenset({FINAL, RECURSIVE, "neutral"})

#: A user function: ``f(env, *args) -> Term``; ``env`` is the running ``Environment``.
UserFunction = Callable[..., Term]


def functor_of(term: Term) -> tuple[str, int] | None:
    """``(name, arity)`` of an atom or structure; None for anything else."""
    term = deref(term)
    if isinstance(term, str):
        return (term, 0)
    if isinstance(term, Struct):
        return (term.functor, term.arity)
    return None


@dataclass(frozen=True, slots=True)
class Arc:
    """``expectation : action => next``; each may be a constant, a pattern or a function."""

    expectation: Term
    action: Term
    next: Term
    place: str = ""  #: where it was written (``file:line:column``)

    @classmethod
    def from_text(cls, text: str, variables: dict[str, Var] | None = None) -> Arc:
        """An arc from ``"Expectation : Action => Next"`` (``variables`` shares names)."""
        from homebot.errors import DialogueError
        from homebot.sitlog.terms import parse_term

        term = deref(parse_term(text, "<arc>", variables))
        if not (isinstance(term, Struct) and term.functor == "=>" and term.arity == 2):
            raise DialogueError(f"an arc is written 'Expectation : Action => Next', not {text!r}")
        left, following = term.args
        if isinstance(left, Struct) and left.functor == ":" and left.arity == 2:
            return cls(left.args[0], left.args[1], following)
        return cls(left, "empty", following)


@dataclass(frozen=True, slots=True)
class Situation:
    """An information state defined by the robot's expectations (Listing 1).

    ``input`` parameterises the perceptual interpreter of a grounded type (the
    question to ask, the placement to look at, the skill to run); ``diag_mod``, on a
    final situation, is unified with the head of its dialogue model (results by
    reference); ``recovery`` names the dialogue model to run when no expectation
    is met ``repeat`` times in a row.
    """

    id: Term
    type: str
    arcs: tuple[Arc, ...] = ()
    in_arg: Term | None = None
    out_arg: Term | None = None
    prog: tuple[Term, ...] = ()
    embedded_dm: Term | None = None
    input: Term | None = None
    interpreter: str | None = None
    diag_mod: Term | None = None
    recovery: Term | None = None
    repeat: int = 3
    place: str = ""

    @property
    def key(self) -> tuple[str, int]:
        found = functor_of(self.id)
        assert found is not None
        return found

    def shared_terms(self) -> tuple[Term | None, ...]:
        """The attributes whose variables are shared by ``prog`` and every arc."""
        return (self.id, self.in_arg, self.out_arg, self.embedded_dm, self.input,
                self.diag_mod, self.recovery)


@dataclass(frozen=True, slots=True)
class DialogueModel:
    """A directed graph of situations with its local variables (Listing A1)."""

    head: Term
    situations: tuple[Situation, ...]
    locals: Mapping[str, Term] = field(default_factory=dict)
    place: str = ""

    @property
    def key(self) -> tuple[str, int]:
        found = functor_of(self.head)
        assert found is not None
        return found

    @property
    def name(self) -> str:
        return self.key[0]

    @property
    def initial(self) -> Situation:
        """The situation called ``is``, else the first one listed."""
        return next((s for s in self.situations if s.key == (INITIAL, 0)), self.situations[0])

    def finals(self) -> list[Situation]:
        return [s for s in self.situations if s.type == FINAL]

    def variables(self) -> list[Var]:
        """The variables of the head (the model's arguments)."""
        from homebot.sitlog.terms import variables_of

        return list(variables_of(self.head))


@dataclass(frozen=True)
class Program:
    """A SitLog program: dialogue models by ``(name, arity)``, globals, user functions."""

    models: Mapping[tuple[str, int], DialogueModel]
    main: tuple[str, int]
    globals: Mapping[str, Term] = field(default_factory=dict)
    functions: Mapping[str, UserFunction] = field(default_factory=dict)
    recovery: Term | None = None
    source: str = "<program>"
    options: Mapping[str, Any] = field(default_factory=dict)
    #: Where the user functions were loaded from (files, modules, entry points), in order.
    function_sources: tuple[str, ...] = ()
    #: Function modules the file names but the loader was told not to run (``sitlog show``):
    #: while any is left out, calls of unknown functions are not errors yet.
    unloaded_functions: tuple[str, ...] = ()

    @classmethod
    def build(cls, models: Sequence[DialogueModel], *, main: str | None = None,
              globals: Mapping[str, Term] | None = None,
              functions: Mapping[str, UserFunction] | None = None,
              recovery: Term | None = None, source: str = "<python>") -> Program:
        """A checked program from models written in Python (the first is main by default)."""
        from homebot.errors import DialogueError
        from homebot.sitlog.validation import check_program

        keyed = {model.key: model for model in models}
        if not keyed or len(keyed) != len(models):
            raise DialogueError(f"{source}: give one or more dialogue models, each name once")
        chosen = next((key for key in keyed if key[0] == main), None) if main else models[0].key
        if chosen is None:
            raise DialogueError(f"{source}: no dialogue model called {main}")
        program = cls(keyed, chosen, dict(globals or {}), dict(functions or {}), recovery, source)
        check_program(program)
        return program

    def model(self, name: str, arity: int = 0) -> DialogueModel:
        return self.models[(name, arity)]

    @property
    def main_model(self) -> DialogueModel:
        return self.models[self.main]
