"""The map of the house: every import in src/homebot goes down DESIGN's ranks, or says why not.

The ranks and DESIGN's rules of the house are data, in ``tests/layers.toml``; the imports
let through for now, each with its reason, in ``tests/layers_allowed.toml``.

Every import counts: at the top of a module, inside a function (a late import is still a
dependency, often one hidden to break a cycle) and under ``if TYPE_CHECKING:`` (a module
whose annotations name another cannot be read, or type-checked, without it; the map is of
what depends on what, not of what Python loads first). Only imports spelled in the code
are seen: a module named in a string and loaded with ``importlib`` is not.

A name imported through a package's ``__init__`` counts against the module that defines
it: ``from homebot.robot import Body`` depends on the Body port (``homebot.robot.body``),
``from homebot.robot import Robot`` on the Robot port (``homebot.robot.port``).
"""

from __future__ import annotations

import ast
import re
import tomllib
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

REPOSITORY = Path(__file__).resolve().parents[1]
SOURCE = REPOSITORY / "src"
RANK_FILE = Path(__file__).with_name("layers.toml")
ALLOW_FILE = Path(__file__).with_name("layers_allowed.toml")
DESIGN = REPOSITORY.parent / "shared" / "DESIGN.md"
INIT = ".__init__"  #: how the rank file names a package's own __init__.py


# ------------------------------------------------------------------ the modules


@dataclass(frozen=True)
class Module:
    """One module of the source tree: ``homebot.sim`` is ``src/homebot/sim/__init__.py``."""

    name: str
    path: Path
    is_package: bool

    @property
    def package(self) -> str:
        """The package relative imports in this module start from."""
        return self.name if self.is_package else self.name.rpartition(".")[0]

    def tree(self) -> ast.Module:
        return ast.parse(self.path.read_text(encoding="utf-8"), str(self.path))


def _modules() -> dict[str, Module]:
    found = {}
    for path in sorted((SOURCE / "homebot").rglob("*.py")):
        parts = list(path.relative_to(SOURCE).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        name = ".".join(parts[:-1] if is_package else parts)
        found[name] = Module(name, path, is_package)
    return found


MODULES = _modules()


def _absolute(module: Module, node: ast.ImportFrom) -> str:
    """The module an ``import from`` names, relative imports resolved."""
    if not node.level:
        return node.module or ""
    base = module.package.split(".")
    base = base[:len(base) - (node.level - 1)]
    return ".".join([*base, *([node.module] if node.module else [])])


def _existing(name: str) -> str:
    """The longest module of the source tree that ``name`` is or lies in."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name


def _reexports(package: Module) -> dict[str, tuple[str, str]]:
    """What a package's ``__init__`` offers from elsewhere: bound name -> (module, name)."""
    offered = {}
    for node in package.tree().body:
        if isinstance(node, ast.ImportFrom):
            source = _absolute(package, node)
            for alias in node.names:
                offered[alias.asname or alias.name] = (source, alias.name)
    return offered


REEXPORTS = {name: _reexports(module) for name, module in MODULES.items() if module.is_package}


def _defining_module(module: str, name: str) -> str:
    """The module that ``from module import name`` depends on: a submodule called ``name``,
    else the module a package's ``__init__`` has the name from, else ``module`` itself."""
    for _ in range(len(MODULES)):  # re-exports of re-exports, never round in a circle
        if f"{module}.{name}" in MODULES:
            return f"{module}.{name}"
        source = REEXPORTS.get(module, {}).get(name)
        if source is None or not source[0].startswith("homebot"):
            return module
        module, name = _existing(source[0]), source[1]
    return module


@dataclass(frozen=True)
class Import:
    """One import of one homebot module by another, where it is written."""

    importer: Module
    line: int
    imported: str  #: the module depended on, re-exports followed

    def where(self) -> str:
        return f"{self.importer.path.relative_to(REPOSITORY)}:{self.line}"


def _imports(module: Module) -> Iterator[Import]:
    """Every import of a homebot module in ``module``, at any depth of the code."""
    for node in ast.walk(module.tree()):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] == "homebot":
                    yield Import(module, node.lineno, _existing(alias.name))
        elif isinstance(node, ast.ImportFrom):
            source = _absolute(module, node)
            if source.split(".")[0] != "homebot":
                continue
            for alias in node.names:
                imported = (_existing(source) if alias.name == "*"
                            else _defining_module(_existing(source), alias.name))
                yield Import(module, node.lineno, imported)


# ------------------------------------------------------------------ the map


def _read(path: Path) -> dict[str, Any]:
    with path.open("rb") as file:
        return tomllib.load(file)


MAP = _read(RANK_FILE)
RANKS: list[str] = [rank["name"] for rank in MAP["rank"]]
PLACES: dict[str, str] = {entry: rank["name"] for rank in MAP["rank"] for entry in rank["modules"]}


def _under(name: str, entry: str) -> bool:
    return name == entry or name.startswith(f"{entry}.")


def _rank_of(module: str) -> str | None:
    """The rank of the longest entry that names ``module`` or a package above it."""
    keys = [f"{module}{INIT}"] if module in MODULES and MODULES[module].is_package else []
    name = module
    while name:
        keys.append(name)
        name = name.rpartition(".")[0]
    return next((PLACES[key] for key in keys if key in PLACES), None)


def _matching(module: str, entries: list[str]) -> str | None:
    """The entry of a rule that ``module`` matches: a rank's name, or a module above it."""
    return next((entry for entry in entries
                 if (_rank_of(module) == entry if entry in RANKS else _under(module, entry))),
                None)


@dataclass(frozen=True)
class Rule:
    """A rule of the house that forbids imports the ranks allow."""

    design: str
    importers: list[str]
    imported: list[str]
    importers_unless: list[str]
    imported_unless: list[str]

    @classmethod
    def of(cls, data: Mapping[str, Any]) -> Rule:
        return cls(data["design"], data["importers"], data["imported"],
                   data.get("importers_unless", []), data.get("imported_unless", []))

    def forbids(self, importer: str, imported: str) -> bool:
        by, of = _matching(importer, self.importers), _matching(imported, self.imported)
        return (by is not None and of is not None and by != of
                and _matching(importer, self.importers_unless) is None
                and _matching(imported, self.imported_unless) is None)


RULES = [Rule.of(rule) for rule in MAP.get("rule", [])]
ALLOWED: dict[tuple[str, str], str] = {
    (entry["importer"], entry["imported"]): entry["why"]
    for entry in _read(ALLOW_FILE).get("allow", [])}


def _violation(found: Import) -> str | None:
    """Why ``found`` breaks the map, or None when it keeps to it."""
    importer, imported = found.importer.name, found.imported
    by, of = _rank_of(importer), _rank_of(imported)
    if by is None or of is None:
        return None  # test_every_module_has_a_rank reports these
    ranks = f"rank {by} -> rank {of}"
    if RANKS.index(of) < RANKS.index(by):
        return f"{ranks}: upward"
    broken = next((rule for rule in RULES if rule.forbids(importer, imported)), None)
    return None if broken is None else f"{ranks}: {broken.design}"


def _every_import() -> list[Import]:
    return [found for module in MODULES.values() for found in _imports(module)]


IMPORTS = _every_import()


# ------------------------------------------------------------------ the tests


def test_every_module_has_a_rank() -> None:
    unplaced = sorted({name for name in MODULES if _rank_of(name) is None}
                      | {found.imported for found in IMPORTS if _rank_of(found.imported) is None})
    assert unplaced == [], f"give these a rank in {RANK_FILE.name}: {unplaced}"


def test_every_import_goes_down_the_ranks_or_is_allowed_with_a_reason() -> None:
    broken: dict[str, None] = {}  # one line per import statement and module, in order
    for found in IMPORTS:
        why = _violation(found)
        if why is not None and (found.importer.name, found.imported) not in ALLOWED:
            broken[f"{found.where()} imports {found.imported} ({why})"] = None
    assert not broken, (
        f"{len(broken)} imports break the map of the house ({RANK_FILE.name}): move the code, "
        f"or allow the import in {ALLOW_FILE.name} saying why.\n" + "\n".join(broken))


def test_every_allowed_import_says_why() -> None:
    assert [pair for pair, why in ALLOWED.items() if not why.strip()] == []


def test_every_allowed_import_is_still_there_and_still_breaks_the_map() -> None:
    """An exception outlives its import only as a false excuse: the list shrinks with the debts."""
    breaking = {(found.importer.name, found.imported) for found in IMPORTS
                if _violation(found) is not None}
    stale = sorted(set(ALLOWED) - breaking)
    assert stale == [], f"delete these entries from {ALLOW_FILE.name}: " + "; ".join(
        f"{importer} -> {imported}" for importer, imported in stale)


def test_the_rules_name_ranks_and_modules_that_exist() -> None:
    entries = {entry for rule in MAP.get("rule", []) for key in
               ("importers", "imported", "importers_unless", "imported_unless")
               for entry in rule.get(key, [])}
    known = set(RANKS) | {name.removesuffix(INIT) for name in PLACES} | {"homebot"}
    unknown = sorted(entry for entry in entries if entry not in known and not any(
        _under(name, entry) for name in MODULES))
    assert unknown == []


def test_imports_in_functions_and_for_type_checking_count(tmp_path: Path) -> None:
    path = tmp_path / "late.py"
    path.write_text("from typing import TYPE_CHECKING\n"
                    "if TYPE_CHECKING:\n    from homebot.robot import Body\n"
                    "def f() -> None:\n    from ..robot import Robot\n    import homebot.errors\n",
                    encoding="utf-8")
    found = _imports(Module("homebot.skills.late", path, is_package=False))
    assert [(late.line, late.imported) for late in found] == [
        (3, "homebot.robot.body"), (5, "homebot.robot.port"), (6, "homebot.errors")]


def test_an_upward_import_is_named_with_both_ranks() -> None:
    upward = Import(MODULES["homebot.world"], 1, "homebot.skills.skill")
    assert _violation(upward) == "rank world -> rank subtask: upward"


def test_a_rule_of_the_house_forbids_an_import_the_ranks_allow() -> None:
    sideways = Import(MODULES["homebot.cli"], 1, "homebot.web")
    assert _violation(sideways) == ("rank interfaces -> rank interfaces: `cli`, `web`, "
                                    "ROS nodes and `bench` call `app`, never each other.")


# The ranks and rules as DESIGN.md writes them: the "Layers" block, row by row.


def _design_rows(text: str) -> list[tuple[str, str]]:
    """DESIGN's layers table as (first line, the row's whole text) per rank."""
    block = text.split("## Layers", 1)[1].split("```", 2)[1]
    rows: list[tuple[str, str]] = []
    for line in block.splitlines():
        if not line.strip():
            continue
        if line[0].isspace() and rows:
            rows[-1] = (rows[-1][0], f"{rows[-1][1]}\n{line}")
        else:
            rows.append((line, line))
    return rows


def _packages(text: str) -> set[str]:
    return set(re.findall(r"homebot\.[a-z_]+", text))


@pytest.mark.acceptance
def test_the_rank_file_agrees_with_design() -> None:
    if not DESIGN.exists():
        pytest.skip("../shared/DESIGN.md is absent")
    text = DESIGN.read_text(encoding="utf-8")
    rows = _design_rows(text)
    assert [row for row, _ in rows if not any(row.startswith(f"{rank} ") for rank in RANKS)] \
        == [], "a rank of DESIGN's table is missing from the rank file"
    assert [next(rank for rank in RANKS if row.startswith(f"{rank} ")) for row, _ in rows] \
        == RANKS
    beyond = set(MAP.get("beyond_design", {}))
    for rank, (_, row) in zip(MAP["rank"], rows, strict=True):
        ours = {".".join(entry.split(".")[:2]) for entry in rank["modules"]
                if entry not in beyond and entry != f"homebot{INIT}"}
        theirs = _packages(row)
        columns = [line[line.index("homebot."):] for line in row.splitlines() if "homebot." in line]
        if any("..." in column for column in columns):  # an open row: it names a few of many
            assert theirs <= ours, rank["name"]
        else:
            assert ours == theirs, rank["name"]
    assert sorted(beyond & _packages(text)) == [], "now in DESIGN: place them by its table"
    flat = " ".join(text.split())
    assert [rule["design"] for rule in MAP.get("rule", [])
            if " ".join(rule["design"].split()) not in flat] == []
