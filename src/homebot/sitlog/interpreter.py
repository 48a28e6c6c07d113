"""SitLog's interpreter: unfolds situations into a recursive transition network (§4).

The interpreter keeps a stack of dialogue models (one ``Frame`` each, with its
local variables and its part of the history), the program's global variables and
the pipe (``in_arg`` → ``out_arg``). Interpreting a situation: bind ``in_arg`` to
the pipe, run ``prog``, evaluate every arc's expectation, obtain the datum from the
perceptual interpreter of the situation's type (or, for a recursive situation,
the final situation its embedded model ended in), take the first arc whose
expectation matches, perform its action, evaluate its next situation, and set
the pipe from ``out_arg`` (unchanged when it is not set). When no expectation is
met the situation is repeated; after ``repeat`` tries its recovery model runs.
A perceptual interpreter or body that cannot go on (the task's time budget is
spent) raises ``RunStopped``: the run ends there, in the final ``stopped(Why)``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from rich.markup import escape

from homebot.errors import DialogueError, HomebotError
from homebot.executive import Executive, RunReport
from homebot.sitlog.evaluation import evaluate
from homebot.sitlog.history import (
    History,
    Transition,
    last_transition,
    render_globals,
    render_history,
    transitions,
)
from homebot.sitlog.model import FINAL, RECURSIVE, DialogueModel, Program, Situation, functor_of
from homebot.sitlog.perception import Body, Perception, RecordingBody, utterance_term
from homebot.sitlog.terms import (
    EMPTY,
    Struct,
    Term,
    Text,
    Trail,
    Var,
    copy_term,
    deref,
    format_term,
    parse_term,
    resolve,
    unify,
)

__all__ = ["DialogueTrace", "Environment", "Frame", "Interpreter", "RunStopped"]

_MAX_RECOVERIES = 3  #: recovery models run for one situation before the run gives up
_MAX_DEPTH = 50  #: dialogue models embedded in one another before the run gives up


class RunStopped(Exception):  # a signal, not an error: the run ends normally
    """Raised by a perceptual interpreter or body when the run must end now.

    ``why`` is a short code (``out_of_time``), ``message`` what to tell a person.
    """

    def __init__(self, why: str, message: str = "") -> None:
        super().__init__(message or why)
        self.why = why
        self.message = message


@dataclass
class Frame:
    """One dialogue model on the stack: its locals, argument bindings and history part."""

    model: DialogueModel
    locals: dict[str, Term]
    mapping: dict[Var, Var]
    history: History
    situation: Situation | None = None


@dataclass
class DialogueTrace:
    """What a SitLog run adds to its report: the final situation reached, the pipe's
    value, the globals, the whole history and how many situations were interpreted."""

    final: Term
    out_arg: Term
    globals: dict[str, Term]
    history: History
    situations: int

    def transitions(self) -> list[Transition]:
        return transitions(self.history)

    def to_dict(self) -> dict[str, Any]:
        return {"final": format_term(self.final), "out_arg": format_term(self.out_arg),
                "globals": {k: format_term(v) for k, v in self.globals.items()},
                "history": render_history(self.history).split("\n"),
                "situations": self.situations}

    def lines(self) -> list[str]:
        """The history as SitLog prints it, then the pipe and the globals."""
        return [escape(render_history(self.history)), "",
                escape(f"Out Arg: {format_term(self.out_arg)}"),
                escape(f"Out Global Vars: {render_globals(self.globals)}")]


class Environment:
    """What expressions and user functions see while a situation is interpreted."""

    def __init__(self, interpreter: Interpreter, frame: Frame) -> None:
        self.interpreter = interpreter
        self.frame = frame
        self.trail = interpreter.trail

    # -- variables -------------------------------------------------------------------------

    def get(self, name: str) -> Term:
        """A local variable of the current model, else a global one."""
        if name in self.frame.locals:
            return self.frame.locals[name]
        if name in self.interpreter.globals:
            return self.interpreter.globals[name]
        raise DialogueError(f"{self.place}: no variable '{name}' in {self.frame.model.name} "
                            "(locals) or in the program's globals")

    def set(self, name: str, value: Term) -> None:
        if name in self.frame.locals:
            self.frame.locals[name] = value
        elif name in self.interpreter.globals:
            self.interpreter.globals[name] = value
        else:
            raise DialogueError(f"{self.place}: no variable '{name}' to set; declare it in "
                                f"the locals of {self.frame.model.name} or in globals")

    # -- context ---------------------------------------------------------------------------

    @property
    def application(self) -> Any:
        """What the program was started with (a KB, a skill context ...); None if nothing."""
        return self.interpreter.application

    @property
    def place(self) -> str:
        situation = self.frame.situation
        return situation.place if situation is not None else self.frame.model.place

    @property
    def situation_name(self) -> str:
        situation = self.frame.situation
        name = format_term(situation.id) if situation is not None else "?"
        return f"{name} of {self.frame.model.name}"

    @property
    def history(self) -> History:
        """The history of the whole task so far (nested lists for embedded models)."""
        return self.interpreter.history

    def history_term(self) -> Term:
        return tuple(t.term() for t in transitions(self.interpreter.history))

    def last_transition(self) -> Term:
        """The last ``Expectation:Action`` of the task's top level (``empty`` at the start)."""
        return last_transition(self.interpreter.history)

    @property
    def models(self) -> list[str]:
        """The dialogue models on the stack, the main one first, the current one last."""
        return [frame.model.name for frame in self.interpreter.stack]

    def function(self, name: str) -> Callable[..., Term]:
        found = self.interpreter.program.functions.get(name)
        if found is None:
            raise DialogueError(f"{self.place}: no user function '{name}'")
        return found

    def say(self, text: str) -> None:
        self.interpreter.body.say(text)


class Interpreter:
    """Runs a ``Program`` with a perception (where data come from) and a body (speech out).

    Args:
        program: the dialogue models, globals and user functions.
        perception: the perceptual interpreters for grounded situation types.
        body: renders ``say``/``screen`` actions (default: remembers them).
        application: anything user functions need (``env.application``).
        max_steps: situations interpreted before the run is stopped as a loop.
        on_transition: told of every transition as it is taken (an event log, a console).
    """

    def __init__(self, program: Program, perception: Perception, *, body: Body | None = None,
                 application: Any = None, max_steps: int = 10_000,
                 on_transition: Callable[[Transition], object] | None = None,
                 executive: Executive | None = None) -> None:
        self.program = program
        self.executive = executive
        self.perception = perception
        self.body: Body = body if body is not None else RecordingBody()
        self.application = application
        self.max_steps = max_steps
        self.on_transition = on_transition
        self.trail = Trail()
        self.globals: dict[str, Term] = {k: copy_term(v) for k, v in program.globals.items()}
        self.history: History = []
        self.stack: list[Frame] = []
        self.steps = 0

    def run(self, call: Term | str | None = None,
            pipe: Term | None = None) -> RunReport[DialogueTrace]:
        """Run the main model (or ``call``, e.g. ``take(malz, Status)``) to its end.

        The run succeeds when it reaches a final situation; stopped (``RunStopped``), it
        ends in ``stopped(Why)`` and fails with the stop's message. With an ``executive``
        (the one the robot's skills run through) the run starts its time budget and the
        report holds the steps it ran, what the robot said and the time it took.
        """
        if isinstance(call, str):
            call = parse_term(call, "<call>")
        call = call if call is not None else copy_term(self.program.main_model.head)
        pipe = pipe if pipe is not None else Var("_Pipe")
        began = self.executive.begin() if self.executive is not None else None
        reason = ""
        try:
            final, pipe = self._run_model(call, pipe, self.history)
        except RunStopped as stop:
            final, reason = Struct("stopped", (stop.why,)), stop.message or stop.why
        trace = DialogueTrace(resolve(final), resolve(pipe), dict(self.globals), self.history,
                              self.steps)
        if self.executive is None or began is None:
            return RunReport(not reason, reason=reason, detail=trace)
        return self.executive.report(began, not reason, reason, trace)

    # -- dialogue models -------------------------------------------------------------------

    def _run_model(self, call: Term, pipe: Term, history: History) -> tuple[Term, Term]:
        key = functor_of(call)
        model = self.program.models.get(key) if key else None
        if model is None:
            raise DialogueError(f"no dialogue model {format_term(call)}; models: "
                                + ", ".join(f"{n}/{a}" for n, a in self.program.models))
        mapping: dict[Var, Var] = {}
        head = copy_term(model.head, mapping)
        if not unify(head, call, self.trail):
            raise DialogueError(f"{model.place}: cannot call {model.name} as {format_term(call)}")
        if len(self.stack) >= _MAX_DEPTH:
            raise DialogueError(f"{model.place}: dialogue models embedded {_MAX_DEPTH} deep; "
                                f"check {model.name} for a recursive situation that never ends")
        frame = Frame(model, {k: copy_term(v) for k, v in model.locals.items()}, mapping, history)
        self.stack.append(frame)
        try:
            next_situation: Term = model.initial.id if not mapping else copy_term(
                model.initial.id, dict(mapping))
            while True:
                situation, own = self._instantiate(frame, next_situation)
                if situation.type == FINAL:
                    return self._final(frame, situation, own, head, pipe)
                next_situation, pipe = self._interpret(frame, situation, own, pipe)
        finally:
            self.stack.pop()

    def _instantiate(self, frame: Frame, wanted: Term) -> tuple[Situation, dict[Var, Var]]:
        for situation in frame.model.situations:
            own = dict(frame.mapping)
            mark = self.trail.mark()
            if unify(copy_term(situation.id, own), wanted, self.trail):
                frame.situation = situation
                return situation, own
            self.trail.undo(mark)
        raise DialogueError(f"{frame.model.place}: {frame.model.name} has no situation "
                            f"{format_term(wanted)}")

    def _final(self, frame: Frame, situation: Situation, own: dict[Var, Var], head: Term,
               pipe: Term) -> tuple[Term, Term]:
        self._count_step(frame)
        if situation.in_arg is not None:
            unify(copy_term(situation.in_arg, own), pipe, self.trail)
        if situation.diag_mod is not None and not unify(
                copy_term(situation.diag_mod, own), head, self.trail):
            raise DialogueError(f"{situation.place}: diag_mod does not match the call "
                                f"{format_term(head)}")
        situation_id = resolve(copy_term(situation.id, own))
        self._record(frame, Transition(frame.model.name, situation_id, EMPTY, EMPTY))
        if situation.out_arg is not None:
            env = Environment(self, frame)
            value = evaluate(copy_term(situation.out_arg, own), env)
            if not isinstance(deref(value), Var):
                pipe = value
        return situation_id, pipe

    # -- situations ------------------------------------------------------------------------

    def _interpret(self, frame: Frame, situation: Situation, own: dict[Var, Var],
                   pipe: Term) -> tuple[Term, Term]:
        env = Environment(self, frame)
        copy = _Copier(own)
        for shared in situation.shared_terms():  # their variables are the same in every arc
            if shared is not None:
                copy(shared)
        if situation.in_arg is not None:
            unify(copy(situation.in_arg), pipe, self.trail)
        tries = recoveries = 0
        while True:  # a situation whose expectations are not met is interpreted again
            self._count_step(frame)
            for expression in situation.prog:
                evaluate(copy.fresh_term(expression), env)
            arcs = [(arc, copy.fresh(arc)) for arc in situation.arcs]
            expectations = [evaluate(expectation, env) for _, (expectation, _, _) in arcs]
            datum, pipe = self._perceive(frame, situation, copy, env, expectations, pipe)
            chosen = self._match(arcs, expectations, datum)
            if chosen is not None:
                break
            tries += 1
            recovery = situation.recovery or self.program.recovery
            if tries < situation.repeat:
                continue
            if recovery is None:
                last = format_term(datum) if datum is not None else "nothing"
                expected = ", ".join(format_term(e) for e in expectations)
                raise DialogueError(
                    f"{situation.place}: no expectation of {env.situation_name} was met "
                    f"{tries} times (last input {last}); expected one of: {expected}; add an "
                    "arc or a recovery model")
            recoveries += 1
            if recoveries > _MAX_RECOVERIES:
                raise DialogueError(f"{situation.place}: {env.situation_name} was not recovered "
                                    f"after {_MAX_RECOVERIES} tries of "
                                    f"{format_term(recovery)}; the dialogue cannot go on")
            recovery_history: History = []
            frame.history.append(recovery_history)
            final, pipe = self._run_model(copy(recovery), pipe, recovery_history)
            chosen = self._match(arcs, expectations, final)
            if chosen is not None:
                datum = final
                break
            tries = 0
        arc_terms, expectation = chosen
        _, action_term, next_term = arc_terms
        action = _action_value(action_term, env)
        following = evaluate(next_term, env)
        self._record(frame, Transition(frame.model.name, resolve(copy(situation.id)),
                                       resolve(expectation), resolve(action), resolve(following)))
        if situation.out_arg is not None:
            value = evaluate(copy(situation.out_arg), env)
            if not isinstance(deref(value), Var):
                pipe = resolve(value)
        return following, pipe

    def _perceive(self, frame: Frame, situation: Situation, copy: _Copier, env: Environment,
                  expectations: list[Term], pipe: Term) -> tuple[Term | None, Term]:
        """The datum to match (and the pipe, which an embedded model may change)."""
        if situation.type == RECURSIVE:
            assert situation.embedded_dm is not None
            embedded = evaluate(copy(situation.embedded_dm), env)
            embedded_history: History = []
            frame.history.append(embedded_history)
            return self._run_model(embedded, pipe, embedded_history)
        request = evaluate(copy(situation.input), env) if situation.input is not None else None
        if situation.type == "neutral":
            return (request if request is not None else EMPTY), pipe
        datum = self.perception.perceive(situation.type, request, expectations, env)
        if situation.interpreter is not None and datum is not None:
            try:
                datum = env.function(situation.interpreter)(env, datum, tuple(expectations))
            except HomebotError:
                raise
            except Exception as error:  # a failure of the user's code is the program's problem
                raise DialogueError(f"{situation.place}: the interpreter {situation.interpreter} "
                                    f"failed: {type(error).__name__}: {error}") from None
        elif isinstance(datum, Text):
            datum = utterance_term(datum.text, expectations)
        return datum, pipe

    def _match(self, arcs: list[tuple[Any, tuple[Term, Term, Term]]], expectations: list[Term],
               datum: Term | None) -> tuple[tuple[Term, Term, Term], Term] | None:
        if datum is None:
            return None
        for (_, arc_terms), expectation in zip(arcs, expectations, strict=True):
            mark = self.trail.mark()
            if unify(expectation, datum, self.trail):
                return arc_terms, expectation
            self.trail.undo(mark)
        return None

    def _record(self, frame: Frame, transition: Transition) -> None:
        frame.history.append(transition)
        if self.on_transition is not None:
            self.on_transition(transition)

    def _count_step(self, frame: Frame) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            raise DialogueError(f"{frame.model.place}: {self.max_steps} situations interpreted "
                                f"without an end; check {frame.model.name} for a loop")


def _action_value(action: Term, env: Environment) -> Term:
    """An action's grounded value; a list holding one function application is its value.

    The paper: for ``[apply(g(X),[_])]`` "the action's value is the specification of
    such transition" (Listing A6 shows the transition itself, not a list of it).
    """
    action = deref(action)
    if isinstance(action, tuple) and len(action) == 1:
        only = deref(action[0])
        if isinstance(only, Struct) and only.functor == "apply" and only.arity == 2:
            return evaluate(only, env)
    return evaluate(action, env)


class _Copier:
    """Copies a situation's terms so its shared variables stay shared, per visit."""

    def __init__(self, own: Mapping[Var, Var]) -> None:
        self.own = dict(own)

    def __call__(self, term: Term) -> Term:
        return copy_term(term, self.own)

    def fresh_term(self, term: Term) -> Term:
        """A copy whose own variables are fresh on every visit (``prog`` has its own scope)."""
        return copy_term(term, dict(self.own))

    def fresh(self, arc: Any) -> tuple[Term, Term, Term]:
        """An arc's expectation, action and next with fresh local variables (one try)."""
        mapping = dict(self.own)
        return (copy_term(arc.expectation, mapping), copy_term(arc.action, mapping),
                copy_term(arc.next, mapping))
