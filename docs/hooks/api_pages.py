"""MkDocs hook: one API reference page per homebot package, found in src/homebot at build time.

The pages are generated rather than written by hand, so a package that is added, moved or
removed changes the reference without anyone editing a list.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import File, Files

SOURCE = Path(__file__).resolve().parents[2] / "src" / "homebot"
# Shipped data, not code.
SKIPPED = {"data"}


def api_modules() -> list[str]:
    """Every package of homebot and every top-level module, dotted, in name order."""
    names = []
    for path in sorted(SOURCE.iterdir()):
        if path.is_dir() and (path / "__init__.py").exists() and path.name not in SKIPPED:
            names.append(f"homebot.{path.name}")
        elif path.suffix == ".py" and path.stem != "__init__" and not path.stem.startswith("_"):
            names.append(f"homebot.{path.stem}")
    return names


def exposes_nothing(module: str) -> bool:
    """Whether a package's ``__init__`` exposes nothing (no ``__all__``, or an empty one):
    its modules are imported one by one, so its page shows them."""
    init = SOURCE / module.removeprefix("homebot.") / "__init__.py"
    if not init.exists():
        return False
    for node in ast.parse(init.read_text(encoding="utf-8")).body:
        target = (node.targets[0] if isinstance(node, ast.Assign)
                  else node.target if isinstance(node, ast.AnnAssign) else None)
        if isinstance(target, ast.Name) and target.id == "__all__" and node.value is not None:
            return not ast.literal_eval(node.value)
    return True


def page_text(module: str) -> str:
    """The page's Markdown: mkdocstrings' directive for the module."""
    if exposes_nothing(module):
        return f"::: {module}\n    options:\n      show_submodules: true\n"
    return f"::: {module}\n"


def _page_path(module: str) -> str:
    return "api/" + module.removeprefix("homebot.") + ".md"


def on_config(config: MkDocsConfig) -> MkDocsConfig:
    nav = config.nav or []
    entries: list[Any] = [{"Overview": "api/index.md"}]
    entries += [{module: _page_path(module)} for module in api_modules()]
    nav.append({"API reference": entries})
    config.nav = nav
    return config


def on_files(files: Files, config: MkDocsConfig) -> Files:
    for module in api_modules():
        files.append(File.generated(config, _page_path(module), content=page_text(module)))
    return files
