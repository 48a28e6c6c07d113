"""``homebot golog maintain PROGRAM``: δ → δ′ with self-maintenance, shown or run with crashes."""

from __future__ import annotations

import argparse
import json
from typing import Any

from rich.console import Console

from homebot import seeds
from homebot.errors import GologError
from homebot.executive import print_report
from homebot.golog.domains import domain_names, domain_theory
from homebot.golog.maintenance import (
    Maintenance,
    MaintenanceInterpreter,
    ProjectionExecutor,
    add_management,
    load_maintenance,
)
from homebot.golog.syntax import parse_program
from homebot.golog.theory import GroundAction, State, Theory
from homebot.scenarios.maintained import run_maintained, shipped_maintenance

__all__ = ["add_parser"]


def add_parser(commands: Any) -> None:
    """Add ``maintain`` to the ``golog`` command group."""
    sub = commands.add_parser("maintain", help="self-maintenance: print the transformed "
                              "program and the todo list, or run it with crashing components")
    sub.add_argument("program", help="a program, e.g. 'rips'")
    sub.add_argument("--domain", default="rips", choices=domain_names())
    sub.add_argument("--maintenance", metavar="FILE",
                     help="a world or robot YAML file with a 'maintenance' section "
                          "(default: the one shipped for the domain)")
    sub.add_argument("--show", action="store_true",
                     help="project the run (no crashes) and print δ′ before every task action, "
                          "its markers and the todo list")
    sub.add_argument("--seed", type=seeds.seed, default=0, help="seed for the crashes")
    sub.add_argument("--json", action="store_true", help="print the result as JSON")
    sub.set_defaults(handler=_maintain)


def _maintenance(args: argparse.Namespace) -> Maintenance:
    if args.maintenance:
        return load_maintenance(args.maintenance)
    if args.domain != "rips":
        raise GologError(f"no maintenance section ships for the domain '{args.domain}'; give "
                         "one with --maintenance FILE")
    return shipped_maintenance(args.domain)


def _theory(args: argparse.Namespace, maintenance: Maintenance) -> Theory:
    theory = add_management(domain_theory(args.domain), maintenance)
    maintenance.check(theory)
    return theory


def _maintain(args: argparse.Namespace) -> int:
    maintenance = _maintenance(args)
    theory = _theory(args, maintenance)
    program = parse_program(args.program, "<command line>")
    if args.show:
        return _show(args, theory, maintenance, program)
    result = run_maintained(program, domain=args.domain, maintenance=maintenance,
                            seed=args.seed)
    if args.json:
        print(json.dumps(result.to_dict(), ensure_ascii=False))
    else:
        print_report(Console(highlight=False), result)
    return 0 if result.success else 1


def _show(args: argparse.Namespace, theory: Theory, maintenance: Maintenance,
          program: Any) -> int:
    def press(clock: int, truth: State) -> list[GroundAction]:
        # the RIPS start button is pressed once the program waits for it
        wanted = "press_start_button" in theory.actions and truth.get(("start_button",)) != "on"
        return [("press_start_button",)] if wanted else []

    interpreter = MaintenanceInterpreter(theory, ProjectionExecutor(theory, events=press),
                                         maintenance, seed=args.seed)
    run = interpreter.run(program)
    steps = [{"action": step.action, "prefix": step.prefix, "markers": step.markers,
              "todo": step.todo, "program": step.program}
             for step in interpreter.transformations]
    executed = [entry["action"] for entry in run.detail.log
                if entry["kind"] == "action" and entry["ok"]]
    if args.json:
        print(json.dumps({"success": run.success, "steps": steps, "transformed": executed},
                         ensure_ascii=False))
        return 0 if run.success else 1
    console = Console(highlight=False, soft_wrap=True)
    for step in steps:
        console.print(f"before {step['action']}:", markup=False)
        console.print(f"  δ′ = {step['program']}", markup=False)
        if step["markers"]:
            console.print(f"  markers: {', '.join(step['markers'])}", markup=False)
        console.print(f"  todo: {', '.join(step['todo']) or '(empty)'}", markup=False)
    console.print("transformed program as run:", markup=False)
    console.print("  " + "; ".join(executed), markup=False)
    console.print("done" if run.success else f"failed: {run.reason}", markup=False)
    return 0 if run.success else 1
