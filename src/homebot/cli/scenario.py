"""``homebot scenario NAME``: run one of the seeds' demonstrations and print its summary.

The command line declares each scenario's shared options (``SHARED_OPTIONS``) with its own
checks and builds its runs with the composition root, ``homebot.app``; the scenario gets
typed values and a run builder (``homebot.scenarios.running``).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from types import ModuleType
from typing import TYPE_CHECKING, Any

import homebot.scenarios.library
from homebot import seeds
from homebot.app import Fidelity, Run, RunSettings, build_run, disturbed
from homebot.cli.modules import add_module_commands, lazy_subparsers, module_names
from homebot.cli.options import add_fidelity_option, disturbance_level, fidelity_of, probability
from homebot.cli.simulated import naming_skills
from homebot.errors import HomebotError
from homebot.events import Event
from homebot.executive.recovery import Protocol
from homebot.navigation import Navigator
from homebot.progress import task
from homebot.scenarios.running import OptionKind, RunBuilder, SharedOption
from homebot.world import DisturbanceModel, PersonModel, World

if TYPE_CHECKING:
    from rich.console import Console

__all__ = ["register", "run_builder", "scenario_names"]


def scenario_names() -> list[str]:
    """Every scenario module in ``homebot.scenarios.library``."""
    return module_names(homebot.scenarios.library)


def run_builder(fidelity: Fidelity = Fidelity.SYMBOLIC, *,
                watch: Callable[[Event], None] | None = None) -> RunBuilder:
    """A scenario's run builder: ``homebot.app.build_run`` in ``fidelity``; ``watch``
    listens to each run's events."""
    def build(world: World, *, seed: int, level: float | None = None,
              disturbances: DisturbanceModel | None = None,
              # a ``homebot.sim.Responder``, spelt out: the simulator is not the CLI's to import
              responder: Callable[[PersonModel, str], str | None] | None = None,
              inference: Protocol | None = None,
              navigator: Navigator | None = None) -> Run:
        run = build_run(RunSettings(
            world=world, seed=seed, fidelity=fidelity,
            disturbances=disturbed(level) if level is not None else disturbances,
            responder=responder, inference=inference, navigator=navigator))
        if watch is not None:
            run.events.listeners.append(watch)
        return run
    return build


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("scenario", help="run a demonstration from the seed papers")
    scenarios = lazy_subparsers(parser, dest="scenario", metavar="NAME")
    add_module_commands(scenarios, homebot.scenarios.library, scenario_names(),
                        add_arguments=_add_arguments, run=_run,
                        exit_status=lambda summary: 0 if summary["success"] else 1)
    parser.set_defaults(handler=lambda args: _missing())


def _add_arguments(module: ModuleType, parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--seed", type=seeds.seed, default=0, help="seed for every random choice")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    shared: tuple[SharedOption, ...] = getattr(module, "SHARED_OPTIONS", ())
    for option in shared:
        if option.kind is OptionKind.FIDELITY:
            add_fidelity_option(parser)
            continue
        check = disturbance_level if option.kind is OptionKind.DISTURBANCE_LEVEL else probability
        parser.add_argument(option.flag, type=check, default=option.default,
                            help=option.help or None)
    module.add_arguments(parser)


def _run(module: ModuleType, args: argparse.Namespace,
         console: Console | None) -> dict[str, Any]:
    doing = f"scenario {args.scenario}"
    with task(doing) as under_way:  # progress names the skill under way, as do's does
        build = run_builder(fidelity_of(args), watch=naming_skills(under_way, doing))
        summary: dict[str, Any] = module.run(args, console, build)
    return summary


def _missing() -> int:
    raise HomebotError(f"name a scenario: {', '.join(scenario_names())}")
