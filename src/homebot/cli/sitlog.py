"""``homebot sitlog run|show|check``: interpret a SitLog program, draw it (§4.3) as dot, or
check it.

``show`` and ``check`` never run a model's code: they read it as data. ``run`` loads the
user functions the model names (only from its own folder, homebot's own modules or
installed entry points; see ``homebot.sitlog.loading``) and says on stderr which.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot import seeds
from homebot.errors import DialogueError
from homebot.executive import print_report
from homebot.files import read_text_file, read_typed_line
from homebot.sitlog import (
    Environment,
    Interpreter,
    Program,
    RecordingBody,
    ScriptedPerception,
    Term,
    dot_diagram,
    format_term,
    load_program,
)
from homebot.sitlog.model import FINAL
from homebot.text import terminal_safe

__all__ = ["register"]

_SPOKEN = frozenset({"speech", "keyboard"})


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("sitlog", help="run or draw a SitLog dialogue model")
    commands = parser.add_subparsers(dest="sitlog_command", metavar="COMMAND")
    run = commands.add_parser(
        "run", help="interpret a SitLog program",
        description="Run a program's main dialogue model (or --call one). Speech input comes "
        "from --input lines, then from --input-file, then from the keyboard; with --world, "
        "vision, people and skill situations run the skills on the simulated robot.")
    run.add_argument("file", help="a dialogue YAML file, or a shipped one (appendix_a, butler, "
                     "behaviours)")
    run.add_argument("--input", action="append", default=[], metavar="TERM",
                     help="one perceived input (SitLog notation or words); repeat in order")
    run.add_argument("--input-file", type=Path, help="inputs, one per line")
    run.add_argument("--call", help="the dialogue model to run, e.g. \"find(cola, [fridge], W)\"")
    run.add_argument("--world", help="run skills on a simulated robot in this world")
    run.add_argument("--seed", type=seeds.seed, default=0, help="seed for the simulated world")
    run.add_argument("--person", help="with --world: speech situations ask this person, who "
                     "answers as the world file scripts")
    run.add_argument("--trace", action="store_true", help="print each transition as it is taken")
    run.add_argument("--json", action="store_true", help="print the result as JSON")
    run.set_defaults(handler=_run)
    show = commands.add_parser("show", help="list a program's models, or draw them as dot "
                               "(runs none of its code)")
    show.add_argument("file", help="a dialogue YAML file, or a shipped one")
    show.add_argument("--dot", action="store_true", help="print the Graphviz diagram (§4.3)")
    show.set_defaults(handler=_show)
    check = commands.add_parser("check", help="check a program without running any of its "
                                "code")
    check.add_argument("file", help="a dialogue YAML file, or a shipped one")
    check.set_defaults(handler=_check)
    parser.set_defaults(handler=_no_command)


def _no_command(args: argparse.Namespace) -> int:
    raise DialogueError("name a sitlog command: run FILE, show FILE [--dot] or check FILE")


@dataclass
class _Mixed:
    """Speech from the script or keyboard; everything else from the robot's skills."""

    spoken: ScriptedPerception
    robot: Any

    def perceive(self, kind: str, request: Term | None, expectations: Sequence[Term],
                 env: Environment) -> Term | None:
        if kind in _SPOKEN:
            return self.spoken.perceive(kind, request, expectations, env)
        result: Term | None = self.robot.perceive(kind, request, expectations, env)
        return result


def _run(args: argparse.Namespace) -> int:
    inputs = list(args.input)
    if args.input_file is not None:
        text = read_text_file(args.input_file, DialogueError, "text", "file of inputs")
        inputs += [line for line in text.splitlines() if line.strip()]
    program = load_program(args.file)
    notes = Console(stderr=True, highlight=False, markup=False, soft_wrap=True)
    for source in program.function_sources:
        notes.print(f"note: user functions from {terminal_safe(source)}")
    console = None if args.json else Console(highlight=False, markup=False)
    keyboard = _prompt if sys.stdin.isatty() and not args.json else None
    spoken = ScriptedPerception(inputs, read_line=keyboard, show=(
        lambda text: console.print(terminal_safe(f"robot asks ({text})"))) if console else None)
    body = RecordingBody(echo=(lambda text: console.print(terminal_safe(f"robot: {text}")))
                         if console else None)
    perception: Any = spoken
    application = executive = None
    if args.person and not args.world:
        raise DialogueError("--person needs --world (the simulated home the person is in)")
    if args.world:
        perception, body_on_robot, application, executive = _on_robot(args, spoken)
        body = body_on_robot
    trace = (lambda step: console.print(terminal_safe(f"  {step}"))) if (
        console and args.trace) else None
    result = Interpreter(program, perception, body=body, application=application,
                         on_transition=trace, executive=executive).run(args.call)
    if args.json:
        print(json.dumps(result.to_dict(), ensure_ascii=False))
        return 0
    # what the robot said was shown as it said it
    print_report(Console(highlight=False), result, speech=False)
    return 0


def _prompt(text: str) -> str:
    return read_typed_line(text, DialogueError)


def _on_robot(args: argparse.Namespace,
              spoken: ScriptedPerception) -> tuple[Any, Any, Any, Any]:
    from homebot.app import RunSettings, build_run
    from homebot.sitlog.robot import SkillBody, SkillPerception
    from homebot.world import World

    run = build_run(RunSettings(world=World.load(args.world), seed=args.seed))
    robot = SkillPerception(run.executive, person=args.person)
    perception = robot if args.person else _Mixed(spoken, robot)
    return perception, SkillBody(run.executive), run.context, run.executive


def _show(args: argparse.Namespace) -> int:
    program = load_program(args.file, run_code=False)
    if args.dot:
        sys.stdout.write(dot_diagram(program))
        return 0
    Console(highlight=False, markup=False).print(terminal_safe(_outline(program), lines=True))
    return 0


def _check(args: argparse.Namespace) -> int:
    program = load_program(args.file, run_code=False)
    situations = sum(len(model.situations) for model in program.models.values())
    models = len(program.models)
    lines = [f"{program.source}: ok: {models} dialogue model{'s' * (models != 1)}, "
             f"{situations} situations, main {program.main[0]}"]
    lines += [f"  functions from {source} (homebot's own)" for source in
              program.function_sources]
    lines += [f"  functions from {source}: not imported (run loads them)" for source in
              program.unloaded_functions]
    print(terminal_safe("\n".join(lines), lines=True))
    return 0


def _outline(program: Program) -> str:
    lines = [f"{program.source}: main {program.main[0]}"]
    for model in program.models.values():
        lines.append(f"{format_term(model.head)}  ({len(model.situations)} situations)")
        for situation in model.situations:
            extra = f" -> {format_term(situation.embedded_dm)}" if (
                situation.embedded_dm is not None) else ""
            lines.append(f"  {format_term(situation.id)} [{situation.type}]{extra}")
            if situation.type == FINAL:
                continue
            for arc in situation.arcs:
                lines.append(f"    {format_term(arc.expectation, operand=True)} : "
                             f"{format_term(arc.action, operand=True)} => "
                             f"{format_term(arc.next)}")
    return "\n".join(lines)
