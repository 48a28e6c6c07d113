"""``homebot plan TASK ARG...``: plan a task with the HTN planner and print the task network."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape

from homebot.beliefs import Beliefs
from homebot.cli.options import add_world_options, load_world
from homebot.errors import PlanningError
from homebot.executive import print_report
from homebot.htn import (
    HOME_TASKS,
    Domain,
    Goal,
    Names,
    PlanActor,
    Planner,
    Problem,
    State,
    goals_from_steps,
    load_domain,
    load_functions,
    plan_dot,
    plans_json,
    read_problems,
    state_from_beliefs,
    task_network_text,
)
from homebot.htn.domain import task_data
from homebot.htn.logic import term_text
from homebot.htn.planner import DEEPEST_DECOMPOSITION
from homebot.knowledge import KnowledgeBase
from homebot.text import terminal_safe
from homebot.world import World

__all__ = ["carry_out_with_htn", "register"]


def register(subparsers: Any) -> None:
    tasks = ", ".join(f"{name} {' '.join(args)}".strip() for name, args in HOME_TASKS.items())
    parser = subparsers.add_parser(
        "plan", help="plan a task with the HTN planner and print the task network",
        description=f"Plan a task from the robot's beliefs in a world. Home tasks: {tasks}.")
    parser.add_argument("task", nargs="?", help="the task, e.g. bring_object (omit with "
                                                "--problem to plan the problem's tasks)")
    parser.add_argument("args", nargs="*", help="its arguments, e.g. pringles Alex")
    add_world_options(parser)
    parser.add_argument("--domain", type=Path,
                        help="a domain file (JSHOP2 syntax, or .py defining domain()) instead "
                             "of the home domain")
    parser.add_argument("--problem", type=Path,
                        help="a JSHOP2 (defproblem ...) file: its atoms are the initial state")
    parser.add_argument("--functions", type=Path, action="append", default=[],
                        metavar="FILE.py",
                        help="Python functions for the domain's (call NAME ...) and :sort-by "
                             "beyond JSHOP2's standard library (JSHOP2 takes them as Java "
                             "classes); repeatable")
    parser.add_argument("--kb", help="a knowledge base saying where objects belong (loc=>PLACE):"
                                     " a file or a shipped KB, e.g. apartment_places")
    parser.add_argument("--all", action="store_true", help="every plan (one per task network)")
    parser.add_argument("--cheapest", action="store_true", help="the plan of least cost")
    parser.add_argument("--limit", type=int, default=1000, help="most plans with --all")
    parser.add_argument("--max-depth", type=int, default=DEEPEST_DECOMPOSITION,
                        help=f"deepest decomposition (at most {DEEPEST_DECOMPOSITION:,})")
    parser.add_argument("--max-expansions", type=int, default=1_000_000,
                        help="most task refinements")
    parser.add_argument("--json", action="store_true",
                        help='print {"plans": [[{"operator": NAME, "args": [...]}, ...], ...]}')
    parser.add_argument("--dot", action="store_true", help="print the task network as Graphviz")
    parser.add_argument("--trace", action="store_true",
                        help="print every refinement the planner tried (why no plan was found)")
    parser.set_defaults(handler=plan)


def _problem(args: argparse.Namespace, domain: Domain) -> Problem | None:
    if args.problem is None:
        return None
    problems = read_problems(args.problem)
    if not problems:
        raise PlanningError(f"{args.problem}: no (defproblem NAME DOMAIN (ATOMS) (TASKS)) found")
    problem = problems[0]
    if problem.domain.lower() != domain.name.lower():  # JSHOP2 names are case-insensitive
        _note(f"{problem.place}: problem {problem.name} is written for domain "
              f"'{problem.domain}', but the domain given is '{domain.name}'; planning with "
              f"'{domain.name}' (give --domain the problem's own domain, or correct its name)")
    return problem


def _note(text: str) -> None:
    """A note on stderr, escaped for the terminal (it quotes names from files)."""
    Console(stderr=True, soft_wrap=True).print(f"note: {terminal_safe(text)}", highlight=False,
                                               markup=False)


def _goal(args: argparse.Namespace, domain: Domain, world: World, names: Names,
          problem: Problem | None) -> tuple[list[tuple[Any, ...]], list[tuple[Any, ...]]]:
    """The tasks to plan and the atoms they add to the state."""
    if args.task is None:
        if problem is None:
            raise PlanningError("give a TASK (e.g. 'homebot plan bring_object pringles Alex') "
                                "or a --problem file")
        return list(problem.tasks), []
    if args.task in HOME_TASKS and args.task in domain.methods:
        goal = Goal.of(args.task, args.args, world, names, domain)
        return [goal.task], list(goal.atoms)
    name = args.task
    if not domain.is_task(name) and domain.is_task(name.lower()):
        name = name.lower()  # JSHOP2 symbols are case-insensitive
    task = task_data([name, *args.args])
    domain.check_task(task, "task")
    return [task], []


def plan(args: argparse.Namespace) -> int:
    if args.limit < 1:
        raise PlanningError(f"--limit {args.limit}: give the most plans to print, 1 or more")
    for option, value in (("--max-depth", args.max_depth),
                          ("--max-expansions", args.max_expansions)):
        if value < 1:
            raise PlanningError(f"{option} {value}: give a bound of 1 or more")
    if args.max_depth > DEEPEST_DECOMPOSITION:
        raise PlanningError(f"--max-depth {args.max_depth}: at most {DEEPEST_DECOMPOSITION:,} "
                            "(each level holds a choice point of the search, about 4 KB)")
    world = load_world(args)
    functions: dict[str, Any] = {}
    for path in args.functions:
        functions.update(load_functions(path))
    domain = load_domain(args.domain, functions)
    for note in domain.notes:
        _note(note)
    problem = _problem(args, domain)
    names = Names()
    if problem is not None:
        state = State(problem.atoms)
    else:
        knowledge = KnowledgeBase.load(args.kb) if args.kb else None
        state, _ = state_from_beliefs(world, Beliefs.from_world(world), world.robot.pose.xy(),
                                      names, knowledge=knowledge)
    tasks, atoms = _goal(args, domain, world, names, problem)
    for atom in atoms:
        state.add(atom)
    planner = Planner(domain, max_depth=args.max_depth, max_expansions=args.max_expansions,
                      trace=args.trace)
    layout = problem.layout if problem is not None and args.task is None else None
    if args.cheapest:
        result = planner.search(state, tasks, limit=None, cheapest=True, layout=layout)
    else:
        result = planner.search(state, tasks, limit=args.limit if args.all else 1,
                                layout=layout)
    if args.json:
        print(json.dumps(plans_json(result.plans, names.name), ensure_ascii=False))
    elif args.dot:
        print(plan_dot(result.plans, " ".join(term_text(item) for item in tasks[0])), end="")
    else:
        console = Console()
        if result.trace is not None:
            console.print("[bold]trace[/]", highlight=False)
            for line in result.trace:
                console.print(f"  {terminal_safe(line)}", highlight=False, markup=False)
        _print(console, result.plans, result.expansions, result.stopped, tasks)
    return 0 if result else 1


def _print(console: Console, plans: list[Any], expansions: int, stopped: str | None,
           tasks: list[tuple[Any, ...]]) -> None:
    goal = escape(terminal_safe(" ".join("(" + " ".join(term_text(item) for item in task) + ")"
                                         for task in tasks)))
    if not plans:
        why = f" (search stopped: {stopped} bound)" if stopped else ""
        console.print(f"[red]no plan[/] for {goal}{why}", highlight=False)
        return
    lengths = sorted(len(plan) for plan in plans)
    stop = f"; stopped by the {stopped} bound" if stopped else ""
    console.print(f"[bold]{len(plans)} plan{'s' * (len(plans) != 1)}[/] for {goal}; "
                  f"shortest {lengths[0]} operators; {expansions} refinements{stop}",
                  highlight=False)
    for number, found in enumerate(plans, start=1):
        console.print(f"\n[bold]task network {number}[/] (cost {found.cost:g})", highlight=False)
        console.print(terminal_safe(task_network_text(found), lines=True), highlight=False,
                      markup=False)
        console.print(f"[bold]plan {number}[/]", highlight=False)
        for index, step in enumerate(found.steps, start=1):
            console.print(f"  {index:2}. {terminal_safe(str(step))}", highlight=False,
                          markup=False)


def carry_out_with_htn(args: argparse.Namespace, world: World, run: Any,
                       steps: list[Any]) -> int | None:
    """``homebot do --planner htn``: plan and act on the parse's goals; None if it has none.

    ``run`` is a ``homebot.app.Run``; with no home task for the parse, a note goes to
    stderr and the caller runs the parsed steps as usual.
    """
    names = Names()
    goals = goals_from_steps(steps, world, names)
    if goals is None:
        Console(stderr=True).print("note: the HTN planner has no task for this command; "
                                   "running the parsed steps", highlight=False)
        return None
    actor = PlanActor(run.executive)
    runs = [actor.run(goal, names) for goal in goals]
    if args.json:
        print(json.dumps({"success": all(runs), "goals": [list(g.task) for g in goals],
                          "runs": [r.to_dict() for r in runs]}, ensure_ascii=False))
    else:
        console = Console()
        for done in runs:
            print_report(console, done)
    return 0 if all(runs) else 1
