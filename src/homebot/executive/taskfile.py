"""Task files: YAML lists of skill steps, checked against the world before anything runs.

A task file is either a list of steps or a mapping with ``description`` and
``steps``; each step is ``{skill: NAME, ARG: VALUE, ...}``::

    description: bring the cola to the operator
    steps:
      - {skill: navigate, to: fridge}
      - {skill: find_object, object: cola, placement: fridge}
      - {skill: pick, object: cola}
      - {skill: navigate, to: operator}
      - {skill: give, person: operator}
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from homebot.errors import TaskError
from homebot.skills import check_step, spelled_as_world
from homebot.task import Step, Task
from homebot.world import World
from homebot.yamlfile import LocatedDocument, load_yaml_document, parse_yaml_text

__all__ = ["MAX_TASK_STEPS", "load_task", "task_from_text", "validate_task"]

#: the most steps a task file may hold: what a person asks for at once is tens of steps (a
#: GPSR command is at most about 15); 20 000 steps ran for minutes before anything was said
MAX_TASK_STEPS = 1_000


def load_task(path: str | Path, world: World) -> Task:
    """Read and check a task file; every problem raises ``TaskError`` naming the line."""
    return _task(load_yaml_document(path, TaskError), world)


def task_from_text(text: str, world: World, source: str = "<task>") -> Task:
    """Read and check a task from YAML text."""
    return _task(parse_yaml_text(text, source, TaskError), world)


def validate_task(task: Task, world: World, source: str = "<task>") -> None:
    """Check every step of an already built task against the world."""
    for index, step in enumerate(task.steps):
        check_step(step, world, f"{source}: step {index + 1}")


def _task(document: LocatedDocument, world: World) -> Task:
    data: Any = document.data
    description = ""
    prefix: list[str | int] = []
    if isinstance(data, dict):
        unknown = sorted(map(str, set(data) - {"description", "steps"}))
        if unknown:
            raise TaskError(f"{document.source}: line {document.line_of([unknown[0]])}: "
                            f"unknown field '{unknown[0]}'; use 'description' and 'steps'")
        description = data.get("description", "")
        if isinstance(description, (list, dict)):
            raise TaskError(f"{document.source}: line {document.line_of(['description'])}: "
                            "description is one line of text, not a list or mapping")
        description = str(description)
        data = data.get("steps")
        prefix = ["steps"]
    if not isinstance(data, list) or not data:
        raise TaskError(f"{document.source}: a task is a non-empty list of steps "
                        "({skill: NAME, ARG: VALUE}), or a mapping with 'steps'")
    if len(data) > MAX_TASK_STEPS:
        raise TaskError(f"{document.source}: line {document.line_of([*prefix, MAX_TASK_STEPS])}: "
                        f"{len(data):,} steps, more than the {MAX_TASK_STEPS:,} a task may have; "
                        "split it into several tasks")
    steps = []
    for index, entry in enumerate(data):
        where = f"{document.source}: line {document.line_of([*prefix, index])}: step {index + 1}"
        if not isinstance(entry, dict) or "skill" not in entry:
            raise TaskError(f"{where}: a step is a mapping with a 'skill' field")
        odd = [key for key in entry if not isinstance(key, str)]
        if odd:
            raise TaskError(f"{where}: argument names are words, not {odd[0]!r}; "
                            "write {skill: NAME, ARG: VALUE}")
        step = spelled_as_world(Step.from_dict(entry), world)  # "patricia" -> "Patrícia"
        check_step(step, world, where)
        steps.append(step)
    return Task(tuple(steps), description)
