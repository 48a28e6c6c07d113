"""Renderers of plans and task networks: indented text, Graphviz DOT, JSON-ready data.

Pure functions of a ``Plan``: they return strings or data and write nothing.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from typing import Any

from homebot.htn.logic import term_text
from homebot.htn.planner import DecompositionNode, Plan

__all__ = ["plan_dot", "plans_json", "task_network_text"]


def _text(task: Sequence[Any]) -> str:
    return "(" + " ".join(term_text(item) for item in task) + ")"


def _children(network: Sequence[DecompositionNode]) -> dict[int, list[int]]:
    children: dict[int, list[int]] = {}
    for index, node in enumerate(network):
        children.setdefault(node.parent, []).append(index)
    return children


def task_network_text(plan: Plan) -> str:
    """The method decomposition tree, one task per line, indented by depth.

    A compound task shows the method branch that refined it in brackets; an
    operator shows its place in the plan (``#1``...).
    """
    children = _children(plan.network)
    position = {step.node: index + 1 for index, step in enumerate(plan.steps)}
    lines: list[str] = []
    stack = [(node, 0) for node in reversed(children.get(-1, []))]
    while stack:
        index, depth = stack.pop()
        node = plan.network[index]
        label = f"[{node.how}]" if node.how is not None else f"#{position.get(index, '?')}"
        lines.append(f"{'  ' * depth}{_text(node.task)}  {label}")
        stack.extend((child, depth + 1) for child in reversed(children.get(index, [])))
    return "\n".join(lines)


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'


def plan_dot(plans: Sequence[Plan], name: str = "task_network") -> str:
    """Graphviz DOT of each plan's task network (one cluster per plan); operators are boxes."""
    lines = [f"digraph {_quote(name)} {{", "  rankdir=TB;", "  node [fontname=Helvetica];"]
    for number, plan in enumerate(plans, start=1):
        prefix = f"p{number}_"
        lines.append(f"  subgraph {_quote('cluster_' + str(number))} {{")
        lines.append(f"    label={_quote(f'plan {number} (cost {plan.cost:g})')};")
        for index, node in enumerate(plan.network):
            label = _text(node.task) + (f"\n[{node.how}]" if node.how else "")
            shape = "box" if node.how is None else "ellipse"
            lines.append(f"    {prefix}{index} [label={_quote(label)}, shape={shape}];")
            if node.parent >= 0:
                lines.append(f"    {prefix}{node.parent} -> {prefix}{index};")
        ordered = [f"{prefix}{step.node}" for step in plan.steps]
        for first, second in itertools.pairwise(ordered):
            lines.append(f"    {first} -> {second} [style=dashed, color=gray, constraint=false];")
        lines.append("  }")
    lines.append("}")
    return "\n".join(lines) + "\n"


def plans_json(plans: Sequence[Plan],
               name: Callable[[Any], Any] = lambda item: item) -> dict[str, Any]:
    """``{"plans": [[{"operator": NAME, "args": [...]}, ...], ...]}``, names mapped by ``name``."""
    return {"plans": [[{"operator": step.operator, "args": [name(arg) for arg in step.args]}
                       for step in plan.steps] for plan in plans]}
