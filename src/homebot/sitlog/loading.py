"""Reading dialogue models from YAML: terms with their place, user functions, includes.

Files ending in ``.dm`` are read in SitLog's own notation (``prolog_form``). The YAML
form mirrors Listing A1: a file holds ``dialogue_models`` (each with an
``id``, ``situations`` and ``locals``), ``globals``, ``functions`` (Python code that
defines ``user_functions()``), ``include`` (other YAML files) and ``main``. Values are
terms in SitLog's notation; an arc is ``"Expectation : Action => Next"`` or
``{expect, action, next}``. Every error names the file, line and column;
``validation.check_program`` runs before a program is returned.

Loading is not running. A model is data a person may have been sent, so what it names
is trusted only from three places: ``.py`` files inside the model's own folder,
homebot's own ``homebot.sitlog.functions`` modules, and modules that an installed
package registers under the entry-point group ``homebot.sitlog_functions``. Anything
else is refused by name before it is imported. With ``run_code=False`` (``sitlog show``
and ``check``) nothing but homebot's own modules is imported at all. ``include`` reads
only files inside the model's folder.
"""

from __future__ import annotations

import difflib
import importlib
import importlib.metadata
import importlib.util
import unicodedata
from collections.abc import Callable, Mapping
from pathlib import Path
from types import ModuleType
from typing import Any

import yaml

from homebot.errors import DialogueError
from homebot.files import read_text_file
from homebot.sitlog.model import Arc, DialogueModel, Program, Situation, UserFunction, functor_of
from homebot.sitlog.terms import EMPTY, MAX_TERM_DEPTH, Struct, Term, Var, parse_term
from homebot.sitlog.validation import check_program
from homebot.yamlfile import compose_yaml_text

__all__ = ["FUNCTION_ENTRY_POINTS", "load_program", "load_program_text",
           "shipped_dialogue_path"]

#: The entry-point group under which an installed package offers SitLog user functions:
#: ``[project.entry-points."homebot.sitlog_functions"] my_functions = "my_package.module"``
#: lets a model write ``functions: [my_functions]``.
FUNCTION_ENTRY_POINTS = "homebot.sitlog_functions"
_SHIPPED_FUNCTIONS = "homebot.sitlog.functions"

_DATA_TOKEN = "$DATA"
_TOP_KEYS = ("dialogue_models", "globals", "functions", "include", "main", "recovery", "types",
             "repeat")
_MODEL_KEYS = ("id", "situations", "locals")
_SITUATION_KEYS = ("id", "type", "in_arg", "out_arg", "prog", "arcs", "embedded_dm", "input",
                   "interpreter", "diag_mod", "recovery", "repeat")
_ARC_KEYS = ("expect", "action", "next")


def _data_directory() -> Path:
    return Path(__file__).resolve().parent.parent / "data" / "dialogue"


def shipped_dialogue_path(spec: str | Path) -> Path:
    """The file a dialogue argument names: a path, ``$DATA/...``, or a shipped file (``butler``,
    ``appendix_a.dm``)."""
    text = str(spec)
    if text.startswith(_DATA_TOKEN):
        return _data_directory().parent / text[len(_DATA_TOKEN):].lstrip("/")
    path = Path(text)
    if path.exists():
        return path
    if "/" not in text:
        for shipped in (_data_directory() / text, _data_directory() / f"{text}.yaml"):
            if shipped.is_file():
                return shipped
    names = ", ".join(sorted(p.name for p in _data_directory().glob("*.*")
                             if p.suffix in (".yaml", ".dm")))
    raise DialogueError(f"no dialogue file '{text}'; give a path or a shipped name ({names})")


def load_program(spec: str | Path, functions: Mapping[str, UserFunction] | None = None, *,
                 run_code: bool = True) -> Program:
    """Load and validate a program from a YAML file (or a shipped name such as ``appendix_a``).

    ``functions`` adds user functions given in Python to those the file names. With
    ``run_code`` false, function modules the file names are not imported (homebot's own
    excepted) and are listed in ``Program.unloaded_functions``; the program can be shown
    and checked, not run.
    """
    path = shipped_dialogue_path(spec)
    reader = _Reader(path.resolve().parent, run_code)
    reader.functions.update(functions or {})
    reader.read_file(path)
    return reader.program(str(path))


def load_program_text(text: str, source: str = "<text>", base: Path | None = None,
                      functions: Mapping[str, UserFunction] | None = None, *,
                      run_code: bool = True) -> Program:
    """Load and validate a program from YAML text; ``base`` (the model's folder, by default
    the working directory) resolves includes and ``.py`` function files."""
    folder = (base or Path.cwd()).resolve()
    reader = _Reader(folder, run_code)
    reader.functions.update(functions or {})
    reader.read_text(text, source, folder)
    return reader.program(source)


class _Reader:
    """Collects models, globals and functions from one file and its includes.

    ``folder`` is the model's own folder: includes and ``.py`` function files must be in
    it (or below it).
    """

    def __init__(self, folder: Path, run_code: bool) -> None:
        self.folder = folder
        self.run_code = run_code
        self.models: dict[tuple[str, int], DialogueModel] = {}
        self.globals: dict[str, Term] = {}
        self.functions: dict[str, UserFunction] = {}
        self.function_sources: list[str] = []
        self.unloaded: list[str] = []
        self.main: tuple[str, int] | None = None
        self.recovery: Term | None = None
        self.types: set[str] = set()
        self.seen: set[Path] = set()

    def program(self, source: str) -> Program:
        if not self.models:
            raise DialogueError(f"{source}: no dialogue_models; add at least one")
        main = self.main or (("main", 0) if ("main", 0) in self.models else next(
            iter(self.models)))
        program = Program(self.models, main, self.globals, self.functions, self.recovery,
                          source, {"types": frozenset(self.types)},
                          tuple(self.function_sources), tuple(self.unloaded))
        check_program(program)
        return program

    def read_file(self, path: Path) -> None:
        path = path.resolve()
        if path in self.seen:
            return
        self.seen.add(path)
        text = read_text_file(path, DialogueError, "yaml", "dialogue model")
        # Accents composed: "josé" written with a combining accent is still one atom.
        text = unicodedata.normalize("NFC", text)
        if path.suffix in (".dm", ".pl"):
            self.read_dm(text, str(path), path.parent)
        else:
            self.read_text(text, str(path), path.parent)

    def read_dm(self, text: str, source: str, base: Path) -> None:
        """A file in SitLog's own notation (``diag_mod/3`` clauses)."""
        from homebot.sitlog.prolog_form import read_dm_text

        found = read_dm_text(text, source)
        file = _File(source, base)
        for spec in found.functions:
            self._functions(file, yaml.ScalarNode("tag:yaml.org,2002:str", spec), spec)
        self.globals.update(found.globals)
        for model in found.models:
            if model.key in self.models:
                raise DialogueError(f"{model.place}: dialogue model {model.name}/{model.key[1]} "
                                    "is defined twice; rename one")
            self.models[model.key] = model
        if found.main is not None:
            self.main = next((key for key in self.models if key[0] == found.main), None)
            if self.main is None:
                raise DialogueError(f"{source}: main({found.main}) names no dialogue model")

    def read_text(self, text: str, source: str, base: Path) -> None:
        root = compose_yaml_text(text, source, DialogueError,
                                 'quote arcs written as "E : A => N"')
        if root is None:
            raise DialogueError(f"{source}: the file is empty; add dialogue_models")
        file = _File(source, base)
        top = file.mapping(root, _TOP_KEYS, "the file")
        if "repeat" in top:
            file.default_repeat = file.repeat(top["repeat"])
        for node in file.sequence(top.get("include"), "include"):
            name = file.string(node, "an include")
            self.read_file(self._inside(base / name, f"{file.place(node)}: include '{name}'"))
        for node in file.sequence(top.get("functions"), "functions"):
            self._functions(file, node)
        for name, node in file.pairs(top.get("globals"), "globals"):
            self.globals[name] = file.term(node, {})
        for node in file.sequence(top.get("types"), "types"):
            self.types.add(file.string(node, "a situation type"))
        if "recovery" in top:
            self.recovery = file.term(top["recovery"], {})
        for node in file.sequence(top.get("dialogue_models"), "dialogue_models"):
            model = file.model(node)
            if model.key in self.models:
                raise DialogueError(f"{model.place}: dialogue model {model.name}/{model.key[1]} "
                                    "is defined twice; rename one")
            self.models[model.key] = model
        if "main" in top:
            main = functor_of(file.term(top["main"], {}))
            if main not in self.models:
                raise DialogueError(f"{file.place(top['main'])}: main names no dialogue model "
                                    f"here; models: {_names(self.models)}")
            self.main = main

    def _inside(self, path: Path, what: str) -> Path:
        """``path`` resolved, if it is inside the model's folder; else a ``DialogueError``
        starting with ``what`` (which says where the path was written)."""
        resolved = path.resolve()
        if not resolved.is_relative_to(self.folder):
            raise DialogueError(f"{what} is outside the model's folder {self.folder}; a model "
                                "reads only files in its own folder: copy the file there")
        return resolved

    def _functions(self, file: _File, node: yaml.Node, spec: str | None = None) -> None:
        spec = spec if spec is not None else file.string(node, "a module or .py file")
        place = file.place(node)
        shipped = spec == _SHIPPED_FUNCTIONS or spec.startswith(_SHIPPED_FUNCTIONS + ".")
        load: Callable[[], Any]
        if spec.endswith(".py"):
            path = self._inside(file.base / spec, f"{place}: functions '{spec}'")
            load, source = (lambda: _module_from_file(path)), str(path)
        elif shipped:
            load, source = (lambda: importlib.import_module(spec)), spec
        else:
            entry = _entry_point(spec)
            if entry is None:
                raise DialogueError(
                    f"{place}: functions '{spec}' is neither a .py file in the model's folder, "
                    f"a module of {_SHIPPED_FUNCTIONS} nor an entry point of the group "
                    f"{FUNCTION_ENTRY_POINTS}; put the .py file beside the model, or register "
                    "the module under that group in its package")
            load, source = entry.load, f"{entry.value} (entry point {spec})"
        if not (self.run_code or shipped):
            self.unloaded.append(source)
            return
        try:
            module = load()
        except Exception as error:  # any failure of the user's code is the file's problem
            raise DialogueError(f"{place}: cannot import functions '{spec}' "
                                f"({error}); fix the module or the name") from None
        if not isinstance(module, ModuleType):
            raise DialogueError(f"{place}: '{spec}' is not a module; an entry point of "
                                f"{FUNCTION_ENTRY_POINTS} names a module, not an object in it")
        self.function_sources.append(source)
        provider = getattr(module, "user_functions", None)
        if not callable(provider):
            raise DialogueError(f"{file.place(node)}: '{spec}' has no user_functions(); define "
                                "one returning {name: function}")
        functions = provider()
        if not isinstance(functions, Mapping):
            raise DialogueError(f"{file.place(node)}: user_functions() of '{spec}' must return "
                                "a mapping of names to functions")
        self.functions.update(functions)


def _module_from_file(path: Path) -> ModuleType:
    if not path.is_file():
        raise ImportError(f"no file {path}")
    module_spec = importlib.util.spec_from_file_location(f"sitlog_user_{path.stem}", path)
    if module_spec is None or module_spec.loader is None:
        raise ImportError(f"{path} is not a Python module")
    module = importlib.util.module_from_spec(module_spec)
    module_spec.loader.exec_module(module)
    return module


def _entry_point(name: str) -> importlib.metadata.EntryPoint | None:
    """The installed entry point ``name`` of the SitLog function group, if any."""
    found = importlib.metadata.entry_points(group=FUNCTION_ENTRY_POINTS, name=name)
    return next(iter(found), None)


class _File:
    """Turns the nodes of one YAML file into model objects, keeping places."""

    def __init__(self, source: str, base: Path) -> None:
        self.source = source
        self.base = base
        self.default_repeat = 3
        self.constructor = yaml.SafeLoader("")

    def place(self, node: yaml.Node) -> str:
        mark = node.start_mark
        if mark is None:
            return self.source
        return f"{self.source}, line {mark.line + 1}, column {mark.column + 1}"

    def mapping(self, node: yaml.Node | None, keys: tuple[str, ...],
                what: str) -> dict[str, yaml.Node]:
        if not isinstance(node, yaml.MappingNode):
            where = self.place(node) if node is not None else self.source
            raise DialogueError(f"{where}: {what} must be a mapping with keys {', '.join(keys)}")
        result: dict[str, yaml.Node] = {}
        for key, value in node.value:
            name = str(key.value)
            if name not in keys:
                guess = difflib.get_close_matches(name, keys, n=1)
                hint = f"did you mean '{guess[0]}'?" if guess else f"keys: {', '.join(keys)}"
                raise DialogueError(f"{self.place(key)}: unknown key '{name}' in {what}; {hint}")
            result[name] = value
        return result

    def sequence(self, node: yaml.Node | None, what: str) -> list[yaml.Node]:
        if node is None or (isinstance(node, yaml.ScalarNode) and node.value in ("", "~")):
            return []
        if not isinstance(node, yaml.SequenceNode):
            raise DialogueError(f"{self.place(node)}: {what} must be a list")
        return list(node.value)

    def pairs(self, node: yaml.Node | None, what: str) -> list[tuple[str, yaml.Node]]:
        if node is None:
            return []
        if not isinstance(node, yaml.MappingNode):
            raise DialogueError(f"{self.place(node)}: {what} must map names to values")
        return [(str(key.value), value) for key, value in node.value]

    def string(self, node: yaml.Node, what: str) -> str:
        if not isinstance(node, yaml.ScalarNode):
            raise DialogueError(f"{self.place(node)}: expected {what}")
        return str(node.value)

    def term(self, node: yaml.Node, variables: dict[str, Var], depth: int = 1) -> Term:
        """A term from a scalar (parsed in SitLog notation) or a YAML list of terms."""
        if isinstance(node, yaml.SequenceNode):
            if depth > MAX_TERM_DEPTH:
                raise DialogueError(f"{self.place(node)}: the lists nest deeper than "
                                    f"{MAX_TERM_DEPTH} levels; flatten them")
            return tuple(self.term(item, variables, depth + 1) for item in node.value)
        if not isinstance(node, yaml.ScalarNode):
            raise DialogueError(f"{self.place(node)}: expected a term, not a mapping")
        if node.tag.startswith("!") or not node.tag.startswith("tag:yaml.org,2002:"):
            raise DialogueError(f"{self.place(node)}: YAML tag {node.tag} means nothing here; "
                                "write the term without it")
        if node.style is None:
            try:
                value = self.constructor.construct_object(node)
            except yaml.YAMLError as error:
                raise DialogueError(f"{self.place(node)}: {error}") from None
            except ValueError:  # Python reads no integer of over 4300 digits
                raise DialogueError(f"{self.place(node)}: a number too long to read; "
                                    "write a smaller one") from None
            if isinstance(value, bool):
                return "true" if value else "false"
            if isinstance(value, int | float):
                return value
            if value is None:
                return EMPTY
        mark = node.start_mark
        offset = mark.column + (1 if node.style in ("'", '"') else 0)
        where = f"{self.source}, line {mark.line + 1}"
        return parse_term(str(node.value), where, variables, offset)

    def repeat(self, node: yaml.Node) -> int:
        value = self.term(node, {})
        if not isinstance(value, int) or value < 1:
            raise DialogueError(f"{self.place(node)}: repeat is a whole number of tries, 1 or "
                                "more")
        return value

    def model(self, node: yaml.Node) -> DialogueModel:
        fields = self.mapping(node, _MODEL_KEYS, "a dialogue model")
        if "id" not in fields:
            raise DialogueError(f"{self.place(node)}: a dialogue model needs an id")
        head_variables: dict[str, Var] = {}
        head = self.term(fields["id"], head_variables)
        if functor_of(head) is None:
            raise DialogueError(f"{self.place(fields['id'])}: a dialogue model's id is a name "
                                "or name(Args)")
        situations = tuple(self.situation(item, head_variables)
                           for item in self.sequence(fields.get("situations"), "situations"))
        if not situations:
            raise DialogueError(f"{self.place(node)}: dialogue model {_show(head)} has no "
                                "situations; add them under situations:")
        local_values = {name: self.term(value, {})
                        for name, value in self.pairs(fields.get("locals"), "locals")}
        return DialogueModel(head, situations, local_values, self.place(node))

    def situation(self, node: yaml.Node, head_variables: dict[str, Var]) -> Situation:
        fields = self.mapping(node, _SITUATION_KEYS, "a situation")
        for needed in ("id", "type"):
            if needed not in fields:
                raise DialogueError(f"{self.place(node)}: a situation needs '{needed}'")
        shared = dict(head_variables)
        values: dict[str, Any] = {}
        for name in ("id", "in_arg", "out_arg", "embedded_dm", "input", "diag_mod", "recovery"):
            if name in fields:
                values[name] = self.term(fields[name], shared)
        if functor_of(values["id"]) is None:
            raise DialogueError(f"{self.place(fields['id'])}: a situation's id is a name or "
                                "name(Args)")
        kind = self.string(fields["type"], "a situation type")
        prog: tuple[Term, ...] = ()
        if "prog" in fields:
            body = self.term(fields["prog"], dict(shared))
            prog = body if isinstance(body, tuple) else (body,)
        arcs = tuple(self.arc(item, shared) for item in self.sequence(fields.get("arcs"), "arcs"))
        repeat = self.repeat(fields["repeat"]) if "repeat" in fields else self.default_repeat
        interpreter = self.string(fields["interpreter"], "a function name") if (
            "interpreter" in fields) else None
        return Situation(values["id"], kind, arcs, values.get("in_arg"), values.get("out_arg"),
                         prog, values.get("embedded_dm"), values.get("input"), interpreter,
                         values.get("diag_mod"), values.get("recovery"), repeat, self.place(node))

    def arc(self, node: yaml.Node, shared: dict[str, Var]) -> Arc:
        variables = dict(shared)
        if isinstance(node, yaml.MappingNode):
            for key, _ in node.value:
                if str(key.value) not in _ARC_KEYS:
                    raise DialogueError(
                        f"{self.place(key)}: '{key.value}' is no key of an arc; write an arc "
                        "as \"Expectation : Action => Next\" (quoted, since YAML reads "
                        "'a: b' as a mapping) or as {expect, action, next}")
            fields = self.mapping(node, _ARC_KEYS, "an arc")
            if "next" not in fields:
                raise DialogueError(f"{self.place(node)}: an arc needs 'next'")
            expectation = self.term(fields["expect"], variables) if "expect" in fields else EMPTY
            action = self.term(fields["action"], variables) if "action" in fields else EMPTY
            return Arc(expectation, action, self.term(fields["next"], variables),
                       self.place(node))
        term = self.term(node, variables)
        if not (isinstance(term, Struct) and term.functor == "=>" and term.arity == 2):
            raise DialogueError(f"{self.place(node)}: an arc is written 'Expectation : Action => "
                                "Next' (quote it in YAML)")
        left, following = term.args
        if isinstance(left, Struct) and left.functor == ":" and left.arity == 2:
            return Arc(left.args[0], left.args[1], following, self.place(node))
        return Arc(left, EMPTY, following, self.place(node))


def _show(term: Term) -> str:
    from homebot.sitlog.terms import format_term

    return format_term(term)


def _names(models: Mapping[tuple[str, int], DialogueModel]) -> str:
    return ", ".join(f"{name}/{arity}" for name, arity in models)
