"""No method of a model object is replaced at run time anywhere in src/ (DESIGN: observers,
not patches).

The check reads every module of ``src/homebot`` with ``ast`` and fails on:

- an assignment ``X.name = F`` where ``F`` is a function (a lambda, a bound method, a
  function defined in the module) and ``name`` is a method some class in src defines
  (``def name``): a method replaced;
- an assignment ``X.name = F`` with ``F`` a function where the same function also reads
  ``X.name``: another object's behaviour wrapped in place, even when ``name`` is a plain
  callable field (a hook) and not a method;
- ``setattr`` (which hides both from the reader and from mypy);
- ``# type: ignore[method-assign]``: mypy's own complaint about a method replaced, silenced.

Setting a documented hook field (``robot.stop_shown = ...``, ``inventory.clock = ...``) is
fine: the class declares a field there, not a method, and nothing is wrapped. ``self.name
= F`` in a class that defines no ``def name`` is a field of the object's own.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "homebot"

#: (module path relative to src/homebot, line's source text) -> why it is not a patch.
ALLOWED: dict[tuple[str, str], str] = {
    ("transport/sim_server.py", "odometry.pose.pose = pose_stamped(types, pose, now).pose"):
        "a ROS message's pose field copied from another message; not Robot.pose",
}


@dataclass(frozen=True)
class Patch:
    where: str  #: file:line
    text: str
    why: str

    def __str__(self) -> str:
        return f"{self.where}: {self.text} ({self.why})"


def _is_property(function: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Whether ``function`` is read as a field (``@property``, ``@cached_property``)."""
    return any(ast.unparse(decorator).split(".")[-1] in ("property", "cached_property")
               for decorator in function.decorator_list)


def _methods(trees: dict[str, ast.Module]) -> set[str]:
    """Every name a class in src defines with ``def``, properties apart: reading a
    property (``run.simulation``) gives a value, not a bound method."""
    return {item.name for tree in trees.values() for node in ast.walk(tree)
            if isinstance(node, ast.ClassDef) for item in node.body
            if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef)
            and not _is_property(item)}


def _functions(tree: ast.Module) -> set[str]:
    """Names the module binds with ``def`` (at module level or nested in functions)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.update(child.name for child in ast.iter_child_nodes(node)
                         if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef)
                         and not isinstance(node, ast.ClassDef))
    names.update(child.name for child in tree.body
                 if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef))
    return names


def _is_function(value: ast.expr, methods: set[str], functions: set[str]) -> bool:
    """Whether ``value`` is a function: a lambda, a bound method or a def of the module."""
    if isinstance(value, ast.Lambda):
        return True
    if isinstance(value, ast.Attribute):
        return value.attr in methods
    return isinstance(value, ast.Name) and value.id in functions


def _is_self(node: ast.expr) -> bool:
    return isinstance(node, ast.Name) and node.id in ("self", "cls")


def patches_in(name: str, tree: ast.Module, source: str, methods: set[str]) -> list[Patch]:
    """The patches in one module (``name``: its path, for the messages)."""
    functions = _functions(tree)
    lines = source.splitlines()
    found: list[Patch] = []

    def report(node: ast.AST, why: str) -> None:
        line = getattr(node, "lineno", 0)
        text = lines[line - 1].strip() if line else ""
        if (name, text) not in ALLOWED:
            found.append(Patch(f"{name}:{line}", text, why))

    own_methods: dict[ast.AST, set[str]] = {}  # each function's class's own methods
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            defined = {item.name for item in node.body
                       if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef)}
            for item in node.body:
                own_methods[item] = defined
    scopes = [node for node in ast.walk(tree)
              if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)] + [tree]
    for scope in scopes:
        reads = {ast.unparse(node) for node in ast.walk(scope)
                 if isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Load)}
        body = scope.body if isinstance(scope, ast.Module) else [scope]
        for statement in (n for part in body for n in ast.walk(part)):
            if not isinstance(statement, ast.Assign | ast.AnnAssign):
                continue
            if statement.value is None or not _is_function(statement.value, methods,
                                                            functions):
                continue
            targets = statement.targets if isinstance(statement, ast.Assign) else [
                statement.target]
            for target in targets:
                if not isinstance(target, ast.Attribute):
                    continue
                if _is_self(target.value):
                    if target.attr in own_methods.get(scope, set()):
                        report(statement, f"replaces its own method {target.attr}")
                elif target.attr in methods:
                    report(statement, f"replaces the method {target.attr} of another object")
                elif ast.unparse(target) in reads:
                    report(statement, f"wraps {ast.unparse(target)} of another object")
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name | ast.Attribute) and (
                ast.unparse(node.func).split(".")[-1] == "setattr"):
            report(node, "setattr")
    for number, line in enumerate(lines, 1):
        if "method-assign" in line and "# type: ignore" in line:
            found.append(Patch(f"{name}:{number}", line.strip(), "a method-assign silenced"))
    return list(dict.fromkeys(found))


def _all_patches(sources: dict[str, str]) -> list[Patch]:
    trees = {name: ast.parse(source, name) for name, source in sources.items()}
    methods = _methods(trees)
    return [patch for name, tree in trees.items()
            for patch in patches_in(name, tree, sources[name], methods)]


def test_no_method_of_a_model_object_is_replaced_at_run_time_in_src() -> None:
    sources = {str(path.relative_to(SRC)): path.read_text(encoding="utf-8")
               for path in sorted(SRC.rglob("*.py"))}
    patches = _all_patches(sources)
    assert not patches, ("methods replaced at run time (observe, subclass or pass the "
                         "callable in instead):\n" + "\n".join(map(str, patches)))


def test_the_check_finds_the_patches_it_is_meant_to_find() -> None:
    # The three kinds homebot had: a method replaced (the console's clock), a hook wrapped
    # in place (the arm's locate), a recorder's nested function (the navigation trace).
    sources = {
        "clock.py": "class Clock:\n    def advance(self, seconds): ...\n",
        "hooks.py": "class Arm:\n    def __init__(self, locate):\n        self.locate = locate\n",
        "console.py": (
            "class Console:\n"
            "    def __init__(self, sim, arm, navigation):\n"
            "        sim.clock.advance = self._paced  # type: ignore[method-assign]\n"
            "        self._given = arm.locate\n"
            "        arm.locate = self._locate\n"
            "        plan_wide = navigation.plan_wide\n"
            "        def traced(*args):\n"
            "            return plan_wide(*args)\n"
            "        navigation.plan_wide = traced\n"
            "        setattr(sim, 'now', lambda: 0.0)\n"
            "        sim.stop_shown = lambda person: False  # a hook field: fine\n"
            "        self.listener = self._heard  # its own field: fine\n"
            "        arm.run = navigation.run  # a property's value, not a method: fine\n"
            "    def _paced(self, before, after): ...\n"
            "    def _locate(self, name): ...\n"
            "    def _heard(self, event): ...\n"
            "class Navigation:\n"
            "    def plan_wide(self, *args): ...\n"
            "    @property\n"
            "    def run(self): ...\n"),
    }
    found = {(patch.where, patch.why) for patch in _all_patches(sources)}
    assert found == {
        ("console.py:3", "replaces the method advance of another object"),
        ("console.py:3", "a method-assign silenced"),
        ("console.py:5", "wraps arm.locate of another object"),
        ("console.py:9", "replaces the method plan_wide of another object"),
        ("console.py:10", "setattr"),
    }
