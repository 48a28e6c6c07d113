"""SitLog's functional language: variables, ``apply``, ``when``, comparisons and basic actions."""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from homebot.errors import DialogueError, HomebotError
from homebot.sitlog.terms import EMPTY, Struct, Term, Text, Var, deref, format_term, resolve, unify

if TYPE_CHECKING:
    from homebot.sitlog.interpreter import Environment

__all__ = ["as_term", "evaluate", "spoken", "truthy"]

_COMPARISONS: Mapping[str, Any] = MappingProxyType({
    "<": lambda a, b: a < b, ">": lambda a, b: a > b,
    "=<": lambda a, b: a <= b, ">=": lambda a, b: a >= b,
    "=:=": lambda a, b: a == b, "=\\=": lambda a, b: a != b,
})
_ARITHMETIC: Mapping[str, Any] = MappingProxyType({
    "+": lambda a, b: a + b, "-": lambda a, b: a - b,
    "*": lambda a, b: a * b, "/": lambda a, b: a / b,
})


def truthy(term: Term) -> bool:
    """Whether a condition's value counts as true (anything but ``false``, ``fail``, unbound)."""
    value = deref(term)
    return not (isinstance(value, Var) or value in ("false", "fail"))


def as_term(value: Any) -> Term:
    """A user function's Python result as a term (lists, booleans and None included)."""
    if value is None:
        return EMPTY
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | tuple):
        return tuple(as_term(item) for item in value)
    if isinstance(value, str | int | float | Text | Struct | Var):
        return value
    raise DialogueError(f"a user function returned {value!r}, which is not a term")


def spoken(term: Term) -> str:
    """The text a ``say`` renders: a text or atom as is, a list joined by spaces."""
    value = resolve(term)
    if isinstance(value, Text | str):
        return str(value)
    if isinstance(value, tuple):
        return " ".join(spoken(item) for item in value)
    return format_term(value)


def evaluate(term: Term, env: Environment) -> Term:
    """The value of an expression in ``env``; plain structures are rebuilt with evaluated args."""
    term = deref(term)
    if isinstance(term, tuple):
        return tuple(evaluate(item, env) for item in term)
    if not isinstance(term, Struct):
        return term
    handler = _OPERATORS.get((term.functor, term.arity))
    if handler is not None:
        value: Term = handler(term, env)
        return value
    if term.arity == 2 and term.functor in _COMPARISONS:
        left, right = (resolve(evaluate(arg, env)) for arg in term.args)
        if isinstance(left, int | float) and isinstance(right, int | float):
            return "true" if _COMPARISONS[term.functor](left, right) else "false"
        return "false"
    if term.arity == 2 and term.functor in _ARITHMETIC:
        left, right = (resolve(evaluate(arg, env)) for arg in term.args)
        if isinstance(left, int | float) and isinstance(right, int | float):
            try:
                return _ARITHMETIC[term.functor](left, right)  # type: ignore[no-any-return]
            except ArithmeticError as error:
                raise DialogueError(f"{env.place}: cannot compute {format_term(term)}: "
                                    f"{error}") from None
        return Struct(term.functor, (left, right))
    return Struct(term.functor, tuple(evaluate(arg, env) for arg in term.args))


def _name(term: Struct, env: Environment) -> str:
    name = deref(evaluate(term.args[0], env))
    if not isinstance(name, str):
        raise DialogueError(f"{env.place}: {term.functor} needs a variable name, got "
                            f"{format_term(name)}")
    return name


def _get(term: Struct, env: Environment) -> Term:
    value = env.get(_name(term, env))
    if term.arity == 2:
        _unify_or_fail(term.args[1], value, env, term)
    return value


def _set(term: Struct, env: Environment) -> Term:
    value = resolve(evaluate(term.args[1], env))
    env.set(_name(term, env), value)
    return value


def _step(delta: int) -> Any:
    def step(term: Struct, env: Environment) -> Term:
        name = _name(term, env)
        value = deref(env.get(name))
        if not isinstance(value, int | float):
            raise DialogueError(f"{env.place}: {term.functor}({name}) needs a number, "
                                f"{name} is {format_term(value)}")
        value = value + delta
        env.set(name, value)
        if term.arity == 2:
            _unify_or_fail(term.args[1], value, env, term)
        return value

    return step


def _assign(term: Struct, env: Environment) -> Term:
    value = evaluate(term.args[1], env)
    _unify_or_fail(term.args[0], value, env, term)
    return value


def _apply(term: Struct, env: Environment) -> Term:
    function = deref(term.args[0])
    if isinstance(function, Struct) and function.functor in ("apply", "get"):
        function = deref(evaluate(function, env))  # a function that yields a function
    arguments = deref(evaluate(term.args[1], env))
    if not isinstance(arguments, tuple):
        raise DialogueError(f"{env.place}: apply needs a list of arguments, got "
                            f"{format_term(arguments)}")
    if isinstance(function, str):
        function = Struct(function, ()) if arguments == () else Struct(
            function, tuple(Var() for _ in arguments))
    if not isinstance(function, Struct) or function.arity != len(arguments):
        raise DialogueError(f"{env.place}: apply({format_term(function)}, ...) needs as many "
                            f"parameters as the {len(arguments)} arguments")
    for parameter, argument in zip(function.args, arguments, strict=True):
        _unify_or_fail(parameter, argument, env, term)
    if function.functor == "when" and function.arity == 3:
        return _when(function, env)
    user_function = env.function(function.functor)
    values = [resolve(arg) for arg in function.args]
    try:
        value = user_function(env, *values)
    except HomebotError:
        raise
    except Exception as error:  # a failure of the user's code is the program's problem
        raise DialogueError(f"{env.place}: the user function {function.functor} failed: "
                            f"{type(error).__name__}: {error}") from None
    return as_term(value)


def _when(term: Struct, env: Environment) -> Term:
    condition = evaluate(term.args[0], env)
    return evaluate(term.args[1] if truthy(condition) else term.args[2], env)


def _equal(term: Struct, env: Environment) -> Term:
    left, right = (resolve(evaluate(arg, env)) for arg in term.args)
    same = _identical(left, right)
    return "true" if same == (term.functor == "==") else "false"


def _identical(left: Term, right: Term) -> bool:
    left, right = deref(left), deref(right)
    if isinstance(left, Var) or isinstance(right, Var):
        return left is right
    if isinstance(left, Struct) and isinstance(right, Struct):
        return left.functor == right.functor and left.arity == right.arity and all(
            _identical(a, b) for a, b in zip(left.args, right.args, strict=True))
    if isinstance(left, tuple) and isinstance(right, tuple):
        return len(left) == len(right) and all(
            _identical(a, b) for a, b in zip(left, right, strict=True))
    return type(left) is type(right) and left == right


def _unifies(term: Struct, env: Environment) -> Term:
    left, right = (evaluate(arg, env) for arg in term.args)
    mark = env.trail.mark()
    if unify(left, right, env.trail):
        return "true" if term.functor == "=" else "false"
    env.trail.undo(mark)
    return "false" if term.functor == "=" else "true"


def _say(term: Struct, env: Environment) -> Term:
    text = spoken(evaluate(term.args[0], env))
    env.say(text)
    return Struct(term.functor, (Text(text),))


def _history(term: Struct, env: Environment) -> Term:
    _unify_or_fail(term.args[0], env.history_term(), env, term)
    return EMPTY


def _unify_or_fail(left: Term, right: Term, env: Environment, where: Struct) -> None:
    if not unify(left, right, env.trail):
        raise DialogueError(f"{env.place}: {format_term(where)} does not hold: "
                            f"{format_term(left)} does not match {format_term(right)}")


_OPERATORS: Mapping[tuple[str, int], Any] = MappingProxyType({
    ("get", 1): _get, ("get", 2): _get, ("set", 2): _set,
    ("inc", 1): _step(1), ("inc", 2): _step(1), ("dec", 1): _step(-1), ("dec", 2): _step(-1),
    ("assign", 2): _assign, ("apply", 2): _apply, ("when", 3): _when,
    ("==", 2): _equal, ("\\==", 2): _equal, ("=", 2): _unifies, ("\\=", 2): _unifies,
    ("say", 1): _say, ("screen", 1): _say, ("history", 1): _history,
})
