"""``homebot golog check|plan|run``: read Golog programs, show solve's policy, run programs."""

from __future__ import annotations

import argparse
import json
from typing import Any

from rich.console import Console

from homebot import seeds
from homebot.errors import GologError
from homebot.executive import print_report
from homebot.golog import Interpreter, SimulatedExecutor, parse_program, policy_text
from homebot.golog.checking import check_theory
from homebot.golog.domains import domain_names, domain_theory
from homebot.golog.library import load_procedures
from homebot.golog.planner import Planner, horizon_of
from homebot.golog.program import Call, Program, Solve
from homebot.golog.semantics import unfold
from homebot.golog.theory import Theory

__all__ = ["register"]

_LINES = 2000  # most lines of a policy printed by 'golog plan' (a policy is a tree)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("golog", help="check, plan and run Golog programs")
    commands = parser.add_subparsers(dest="golog_command", metavar="COMMAND")
    check = commands.add_parser("check", help="read a program file and report problems")
    check.add_argument("file", help="a .golog file of 'proc NAME ... endproc'")
    check.add_argument("--domain", choices=domain_names(),
                       help="also check names and arities against this domain's theory")
    check.set_defaults(handler=_check)
    for name, text in (("plan", "print the policy solve plans, with its markers"),
                       ("run", "run a program on a pure simulation of the domain")):
        sub = commands.add_parser(name, help=text)
        sub.add_argument("program", help="a program, e.g. 'sort_cups(red, green, blue, 4)'")
        sub.add_argument("--domain", required=True, choices=domain_names())
        sub.add_argument("--file", help="a .golog file whose procedures to add to the domain")
        sub.add_argument("--seed", type=seeds.seed, default=0, help="seed for every random choice")
        sub.add_argument("--json", action="store_true", help="print the result as JSON")
        sub.set_defaults(handler=_plan if name == "plan" else _run)
    from homebot.cli.golog_maintain import add_parser

    add_parser(commands)
    parser.set_defaults(handler=_no_command)


def _no_command(args: argparse.Namespace) -> int:
    raise GologError("name a golog command: check, plan, run or maintain")


def _theory(args: argparse.Namespace) -> Theory:
    theory = domain_theory(args.domain)
    if getattr(args, "file", None):
        theory.define(*load_procedures(args.file))
    check_theory(theory)
    return theory


def _check(args: argparse.Namespace) -> int:
    procedures = load_procedures(args.file)
    if not procedures:
        raise GologError(f"{args.file}: the file is empty (it defines no procedure); write at "
                         "least one 'proc NAME ... endproc'")
    if args.domain:
        theory = domain_theory(args.domain)
        theory.define(*procedures)
        check_theory(theory)
    names = ", ".join(procedure.name for procedure in procedures) or "none"
    print(f"{args.file}: {len(procedures)} procedure(s) ({names}); no problems found")
    return 0


def _solve_in(program: Program, theory: Theory) -> Solve:
    for _ in range(50):
        if isinstance(program, Solve):
            return program
        if isinstance(program, Call) and program.name in theory.procedures:
            program = unfold(program, theory, theory.initial)
            continue
        break
    raise GologError(f"'{program}' does not begin with solve(...); plan a procedure whose "
                     f"body is a solve, such as sort_cups or navigate")


def _plan(args: argparse.Namespace) -> int:
    theory = _theory(args)
    solve = _solve_in(parse_program(args.program, "<command line>"), theory)
    planner = Planner(theory, solve.reward)
    result = planner.solve(solve.body, theory.initial, horizon_of(theory, solve, theory.initial))
    if args.json:
        print(json.dumps({"value": result.value, "probability": result.probability,
                          "nodes": planner.nodes,
                          "policy": policy_text(result.policy, limit=_LINES)}, ensure_ascii=False))
    else:
        console = Console(highlight=False)
        console.print(policy_text(result.policy, limit=_LINES), markup=False)
        console.print(f"value {result.value:g}, success probability {result.probability:g}, "
                      f"{planner.nodes} nodes expanded")
    return 0


def _run(args: argparse.Namespace) -> int:
    theory = _theory(args)
    program = parse_program(args.program, "<command line>")
    run = Interpreter(theory, SimulatedExecutor(theory, seed=args.seed),
                      seed=args.seed).run(program)
    if args.json:
        print(json.dumps(run.to_dict(), ensure_ascii=False))
    else:
        print_report(Console(highlight=False), run)
    return 0 if run.success else 1
