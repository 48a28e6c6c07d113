"""Program constructs of Golog / READYLOG as frozen dataclasses (structural equality).

Every node can substitute constants for variables (``pi``, ``pickBest`` and
procedure parameters bind them) and prints itself in the textual syntax.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from homebot.golog.expressions import Expr, Substitution

__all__ = [
    "Call",
    "Choice",
    "Conc",
    "If",
    "Nil",
    "Pi",
    "PickBest",
    "Prob",
    "Procedure",
    "Program",
    "Search",
    "Seq",
    "Solve",
    "Star",
    "Test",
    "WaitFor",
    "While",
    "WithCtrl",
    "WithPol",
]


class Program:
    """A Golog program."""

    __slots__ = ()

    def substitute(self, bindings: Substitution) -> Program:
        raise NotImplementedError


@dataclass(frozen=True, slots=True)
class Nil(Program):
    """The empty program."""

    def substitute(self, bindings: Substitution) -> Program:
        return self

    def __str__(self) -> str:
        return "nil"


@dataclass(frozen=True, slots=True)
class Call(Program):
    """A primitive action or a procedure call, resolved by name against the theory."""

    name: str
    args: tuple[Expr, ...] = ()

    def substitute(self, bindings: Substitution) -> Program:
        if not self.args:
            return self
        return Call(self.name, tuple(arg.substitute(bindings) for arg in self.args))

    def __str__(self) -> str:
        if not self.args:
            return self.name
        return f"{self.name}({', '.join(str(arg) for arg in self.args)})"


@dataclass(frozen=True, slots=True)
class Test(Program):
    """``?(φ)``: go on only if φ holds."""

    condition: Expr

    def substitute(self, bindings: Substitution) -> Program:
        return Test(self.condition.substitute(bindings))

    def __str__(self) -> str:
        return f"?({self.condition})"


@dataclass(frozen=True, slots=True)
class Seq(Program):
    """``δ1; δ2; ...``."""

    parts: tuple[Program, ...]

    def substitute(self, bindings: Substitution) -> Program:
        return Seq(tuple(part.substitute(bindings) for part in self.parts))

    def __str__(self) -> str:
        return "; ".join(_grouped(part) for part in self.parts)


@dataclass(frozen=True, slots=True)
class If(Program):
    """``if φ then δ1 else δ2 endif``."""

    condition: Expr
    then: Program
    otherwise: Program = Nil()

    def substitute(self, bindings: Substitution) -> Program:
        return If(self.condition.substitute(bindings), self.then.substitute(bindings),
                  self.otherwise.substitute(bindings))

    def __str__(self) -> str:
        return f"if {self.condition} then {self.then} else {self.otherwise} endif"


@dataclass(frozen=True, slots=True)
class While(Program):
    """``while φ do δ endwhile``."""

    condition: Expr
    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return While(self.condition.substitute(bindings), self.body.substitute(bindings))

    def __str__(self) -> str:
        return f"while {self.condition} do {self.body} endwhile"


@dataclass(frozen=True, slots=True)
class Choice(Program):
    """``δ1 | δ2 | ...``: nondeterministic choice."""

    options: tuple[Program, ...]

    def substitute(self, bindings: Substitution) -> Program:
        return Choice(tuple(option.substitute(bindings) for option in self.options))

    def __str__(self) -> str:
        return "(" + " | ".join(_grouped(option) for option in self.options) + ")"


@dataclass(frozen=True, slots=True)
class Star(Program):
    """``star(δ)``: do δ zero or more times."""

    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Star(self.body.substitute(bindings))

    def __str__(self) -> str:
        return f"star({self.body})"


def _inner(variable: str, bindings: Substitution) -> Substitution:
    return {name: value for name, value in bindings.items() if name != variable}


@dataclass(frozen=True, slots=True)
class Pi(Program):
    """``pi(x, {d1, ...}, δ)``: some value of x from a finite domain."""

    variable: str
    domain: Expr
    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Pi(self.variable, self.domain.substitute(bindings),
                  self.body.substitute(_inner(self.variable, bindings)))

    def __str__(self) -> str:
        return f"pi({self.variable}, {self.domain}, {self.body})"


@dataclass(frozen=True, slots=True)
class PickBest(Program):
    """``pickBest(x, {d1, ...}, δ)``: the value of x that makes δ's policy best."""

    variable: str
    domain: Expr
    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return PickBest(self.variable, self.domain.substitute(bindings),
                        self.body.substitute(_inner(self.variable, bindings)))

    def __str__(self) -> str:
        return f"pickBest({self.variable}, {self.domain}, {self.body})"


@dataclass(frozen=True, slots=True)
class Conc(Program):
    """``σ1 || σ2``: prioritised concurrency; σ1 goes first, ends when either ends."""

    high: Program
    low: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Conc(self.high.substitute(bindings), self.low.substitute(bindings))

    def __str__(self) -> str:
        return f"({_grouped(self.high)} || {_grouped(self.low)})"


@dataclass(frozen=True, slots=True)
class WithPol(Program):
    """``withPol(σ1, σ2)``: ``(σ1; ?(false)) || σ2``, so it ends when σ2 ends."""

    policy: Program
    program: Program

    def substitute(self, bindings: Substitution) -> Program:
        return WithPol(self.policy.substitute(bindings), self.program.substitute(bindings))

    def __str__(self) -> str:
        return f"withPol({self.policy}, {self.program})"


@dataclass(frozen=True, slots=True)
class WithCtrl(Program):
    """``withCtrl φ do σ endwithCtrl``: σ advances only while φ holds."""

    condition: Expr
    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return WithCtrl(self.condition.substitute(bindings), self.body.substitute(bindings))

    def __str__(self) -> str:
        return f"withCtrl {self.condition} do {self.body} endwithCtrl"


@dataclass(frozen=True, slots=True)
class WaitFor(Program):
    """``waitFor(τ)``: pause until τ holds."""

    condition: Expr

    def substitute(self, bindings: Substitution) -> Program:
        return WaitFor(self.condition.substitute(bindings))

    def __str__(self) -> str:
        return f"waitFor({self.condition})"


@dataclass(frozen=True, slots=True)
class Prob(Program):
    """``prob(p, σ1, σ2)``: σ1 happens with probability p, σ2 otherwise."""

    probability: Expr
    first: Program
    second: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Prob(self.probability.substitute(bindings), self.first.substitute(bindings),
                    self.second.substitute(bindings))

    def __str__(self) -> str:
        return f"prob({self.probability}, {self.first}, {self.second})"


@dataclass(frozen=True, slots=True)
class Solve(Program):
    """``solve(h, reward, σ)``: plan the best policy for σ up to horizon h, then run it."""

    horizon: Expr
    reward: Expr
    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Solve(self.horizon.substitute(bindings), self.reward.substitute(bindings),
                     self.body.substitute(bindings))

    def __str__(self) -> str:
        return f"solve({self.horizon}, {self.reward}, {self.body})"


@dataclass(frozen=True, slots=True)
class Search(Program):
    """``search(δ)``: IndiGolog's Σ; online, take only steps from which δ can still end."""

    body: Program

    def substitute(self, bindings: Substitution) -> Program:
        return Search(self.body.substitute(bindings))

    def __str__(self) -> str:
        return f"search({self.body})"


@dataclass(frozen=True, slots=True)
class Procedure:
    """``proc name(params) body endproc``; recursive calls are allowed."""

    name: str
    parameters: tuple[str, ...]
    body: Program
    #: where each name in the body is first written ("file:line:column"), when read from text
    places: dict[str, str] = field(default_factory=dict, compare=False, repr=False)

    def __str__(self) -> str:
        head = f"{self.name}({', '.join(self.parameters)})" if self.parameters else self.name
        return f"proc {head}\n  {self.body}\nendproc"


def _grouped(program: Program) -> str:
    if isinstance(program, Seq | Choice):
        return f"({program})"
    return str(program)
