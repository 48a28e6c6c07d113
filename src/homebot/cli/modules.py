"""Command groups whose subcommands are the modules of a package (benchmarks, scenarios).

Each module exposes ``add_arguments(parser)`` and ``run(args, console) -> dict``; the
subcommand prints the dict as JSON under ``--json`` (``console`` is then None).
"""

from __future__ import annotations

import argparse
import importlib
import json
import pkgutil
from collections.abc import Callable, Collection
from types import ModuleType
from typing import Any

from rich.console import Console

__all__ = ["add_module_commands", "module_names"]


def module_names(package: ModuleType, exclude: Collection[str] = ()) -> list[str]:
    """The modules of ``package``, sorted, but for ``exclude``."""
    return sorted(module.name for module in pkgutil.iter_modules(package.__path__)
                  if module.name not in exclude)


def add_module_commands(subparsers: Any, package: ModuleType, names: list[str], *,
                        add_common: Callable[[argparse.ArgumentParser], None],
                        exit_status: Callable[[dict[str, Any]], int]) -> None:
    """One subcommand per module, with its own arguments and the common ones."""
    for name in names:
        module = importlib.import_module(f"{package.__name__}.{name}")
        sub = subparsers.add_parser(name, help=(module.__doc__ or "").strip().splitlines()[0])
        add_common(sub)
        module.add_arguments(sub)
        sub.set_defaults(handler=_runner(module, exit_status))


def _runner(module: ModuleType,
            exit_status: Callable[[dict[str, Any]], int]) -> Callable[[argparse.Namespace], int]:
    def handler(args: argparse.Namespace) -> int:
        result: dict[str, Any] = module.run(args, None if args.json else Console())
        if args.json:
            print(json.dumps(result))
        return exit_status(result)
    return handler
