"""Lazily built sub-commands, and command groups whose sub-commands are a package's modules.

``LazySubcommands`` is the argparse action behind every level of ``homebot``: a sub-command
is declared by name and help line, and its module is imported only when the command line
chooses it, so ``homebot --help`` imports no engine and each command imports what it uses.

``add_module_commands`` makes one sub-command per module of a package (the scenarios; the
benchmarks have an explicit registry, ``homebot.bench.BENCHMARKS``). The caller says how a
module declares its arguments (``add_arguments(module, parser)``) and how it runs
(``run(module, args, console) -> dict``); the sub-command prints the dict as JSON under
``--json`` (``console`` is then None). The help line is the first line
of the module's docstring, read from its source without importing it.
"""

from __future__ import annotations

import argparse
import ast
import importlib
import importlib.util
import json
import pkgutil
from collections.abc import Callable, Collection
from types import ModuleType
from typing import TYPE_CHECKING, Any, cast

__all__ = ["LazySubcommands", "add_module_commands", "lazy_subparsers", "module_names"]


if TYPE_CHECKING:
    from rich.console import Console

    _SubParsers = argparse._SubParsersAction[argparse.ArgumentParser]
else:
    _SubParsers = argparse._SubParsersAction


class LazySubcommands(_SubParsers):
    """A sub-parsers action whose entries are registered only when the command line picks them.

    Use it as ``parser.add_subparsers(action=LazySubcommands, ...)``, then
    ``add_lazy(name, help, register)``: ``register(self)`` runs when ``name`` is chosen and
    calls ``self.add_parser(name, ...)`` itself, which replaces the placeholder in place.
    Until then only ``name`` and its help line exist, which is all the group's ``--help`` shows.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._pending: dict[str, Callable[[LazySubcommands], None]] = {}
        self._placeholders: set[str] = set()

    def add_lazy(self, name: str, help: str,
                 register: Callable[[LazySubcommands], None]) -> None:
        """Declare ``name`` with its help line; ``register(self)`` builds it when chosen."""
        self.add_parser(name, help=help)
        self._placeholders.add(name)
        self._pending[name] = register

    def load(self, name: str) -> None:
        """Build ``name``'s parser now (done by itself when the command line chooses it)."""
        register = self._pending.pop(name, None)
        if register is not None:
            register(self)

    def load_all(self) -> None:
        """Build every pending parser (for tests or documentation of the whole command line)."""
        for name in list(self._pending):
            self.load(name)

    def add_parser(self, name: str, **kwargs: Any) -> argparse.ArgumentParser:
        if name not in self._placeholders:
            return super().add_parser(name, **kwargs)
        self._placeholders.discard(name)
        del self._name_parser_map[name]
        index = next(i for i, choice in enumerate(self._choices_actions) if choice.dest == name)
        del self._choices_actions[index]
        parser = super().add_parser(name, **kwargs)
        # The real entry keeps its placeholder's place in the help.
        self._choices_actions.insert(index, self._choices_actions.pop())
        return parser

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        self.load(values[0])
        super().__call__(parser, namespace, values, option_string)


def lazy_subparsers(parser: argparse.ArgumentParser, **kwargs: Any) -> LazySubcommands:
    """``parser.add_subparsers(**kwargs)`` with lazily built entries."""
    return cast(LazySubcommands, parser.add_subparsers(action=LazySubcommands, **kwargs))


def module_names(package: ModuleType, exclude: Collection[str] = ()) -> list[str]:
    """The modules of ``package``, sorted, but for ``exclude``."""
    return sorted(module.name for module in pkgutil.iter_modules(package.__path__)
                  if module.name not in exclude)


def module_help(module_name: str) -> str:
    """The first line of a module's docstring, read from its source without importing it."""
    spec = importlib.util.find_spec(module_name)
    if spec is None or spec.origin is None:
        return ""
    with open(spec.origin, encoding="utf-8") as source:
        docstring = ast.get_docstring(ast.parse(source.read())) or ""
    return docstring.strip().splitlines()[0] if docstring.strip() else ""


AddArguments = Callable[[ModuleType, argparse.ArgumentParser], None]
RunModule = Callable[[ModuleType, argparse.Namespace, "Console | None"], dict[str, Any]]


def add_module_commands(subparsers: LazySubcommands, package: ModuleType, names: list[str], *,
                        add_arguments: AddArguments, run: RunModule,
                        exit_status: Callable[[dict[str, Any]], int]) -> None:
    """One lazily built sub-command per module, with the arguments ``add_arguments`` gives it."""
    for name in names:
        qualified = f"{package.__name__}.{name}"
        subparsers.add_lazy(name, module_help(qualified),
                            _module_register(qualified, name, add_arguments, run, exit_status))


def _module_register(qualified: str, name: str, add_arguments: AddArguments, run: RunModule,
                     exit_status: Callable[[dict[str, Any]], int],
                     ) -> Callable[[LazySubcommands], None]:
    def register(subparsers: LazySubcommands) -> None:
        module = importlib.import_module(qualified)
        sub = subparsers.add_parser(name, help=module_help(qualified))
        add_arguments(module, sub)
        sub.set_defaults(handler=_runner(module, run, exit_status))
    return register


def _runner(module: ModuleType, run: RunModule,
            exit_status: Callable[[dict[str, Any]], int]) -> Callable[[argparse.Namespace], int]:
    def handler(args: argparse.Namespace) -> int:
        from rich.console import Console

        result = run(module, args, None if args.json else Console())
        if args.json:
            print(json.dumps(result, ensure_ascii=False))
        return exit_status(result)
    return handler
