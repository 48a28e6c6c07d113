"""Read and write KB files in the paper's syntax: a list of ``class(Id, Mother, ...)`` terms."""

from __future__ import annotations

from pathlib import Path

from homebot.errors import KnowledgeError
from homebot.files import read_text_file
from homebot.knowledge import coherence
from homebot.knowledge.model import (
    ANY,
    ClassNode,
    IndividualNode,
    Kind,
    Statement,
    Taxonomy,
)
from homebot.knowledge.terms import (
    TermParser,
    TermShapeError,
    format_atom,
    format_entry,
    statement_from_term,
)

__all__ = [
    "kb_warnings",
    "read_kb",
    "read_kb_file_text",
    "read_kb_text",
    "write_kb",
    "write_kb_text",
]

_NONE = "none"


class _KBParser(TermParser):
    """The KB-level grammar on top of the term parser; remembers where things are."""

    __slots__ = ("class_at", "individual_at", "mother_at", "statement_at")

    def __init__(self, text: str, source: str) -> None:
        super().__init__(text, source)
        self.class_at: dict[str, int] = {}
        self.mother_at: dict[str, int] = {}
        self.individual_at: dict[str, int] = {}
        self.statement_at: dict[tuple[str, Kind, int], int] = {}

    def knowledge_base(self) -> Taxonomy:
        taxonomy = Taxonomy()
        self.expect("[", "'[' opening the list of class(...) terms")
        if self.tokens[self.index] != "]":
            self.class_term(taxonomy)
            while self.tokens[self.index] == ",":
                self.index += 1
                self.class_term(taxonomy)
        self.expect("]", "',' or ']' closing the list of classes")
        if self.tokens[self.index] == ".":
            self.index += 1
        if not self.at_end():
            raise self.error("the end of the KB after its closing ']'")
        return taxonomy

    def name(self, what: str) -> str:
        token = self.tokens[self.index]
        first = token[:1]
        if ("a" <= first <= "z") or (first == "'" and len(token) > 1 and token.endswith("'")):
            value = self.primary()
            if isinstance(value, str) and value and value != ANY:
                return value
            self.index -= 1
        raise self.error(what)

    def class_term(self, taxonomy: Taxonomy) -> None:
        start = self.index
        if self.tokens[start] != "class":
            raise self.error("class(Id, Mother, Properties, Relations, Individuals)")
        self.index += 1
        self.expect("(", "'(' after class")
        name_at = self.index
        name = self.name("a class name")
        if name in taxonomy.classes or name == _NONE:
            found = "'none' (it marks top's missing mother)" if name == _NONE else f"'{name}' again"
            raise self.error("a class name not used before", index=name_at, found=found)
        self.expect(",", "',' after the class name")
        self.mother_at[name] = self.index
        mother: str | None = self.name("the mother class (or none for top)")
        if mother == _NONE:
            mother = None
        node = ClassNode(name, mother)
        taxonomy.classes[name] = node
        self.class_at[name] = name_at
        self.expect(",", "',' after the mother class")
        node.properties = self.statements(name, Kind.PROPERTY)
        self.expect(",", "',' after the property list")
        node.relations = self.statements(name, Kind.RELATION)
        self.expect(",", "',' after the relation list")
        self.expect("[", "'[' opening the list of individuals")
        if self.tokens[self.index] != "]":
            self.individual(taxonomy, node)
            while self.tokens[self.index] == ",":
                self.index += 1
                self.individual(taxonomy, node)
        self.expect("]", "',' or ']' closing the list of individuals")
        self.expect(")", "')' closing class(...)")

    def individual(self, taxonomy: Taxonomy, node: ClassNode) -> None:
        self.expect("[", "'[id=>Name, Properties, Relations]' for an individual")
        self.expect("id", "id=>Name starting an individual")
        self.expect("=>", "'=>' after id")
        name_at = self.index
        name = self.name("the individual's name")
        if name in taxonomy.individuals or name in self.class_at:
            raise self.error("a name not used before", index=name_at, found=f"'{name}' again")
        self.individual_at[name] = name_at
        self.expect(",", "',' after the individual's name")
        properties = self.statements(name, Kind.PROPERTY)
        self.expect(",", "',' after the individual's properties")
        relations = self.statements(name, Kind.RELATION)
        self.expect("]", "']' closing the individual")
        taxonomy.individuals[name] = IndividualNode(name, node.name, properties, relations)
        node.individuals.append(name)

    def statements(self, owner: str, kind: Kind) -> list[Statement]:
        tokens = self.tokens
        self.expect("[", f"'[' opening the {kind.value} list")
        result: list[Statement] = []
        if tokens[self.index] == "]":
            self.index += 1
            return result
        while True:
            entry_at = self.index
            self.expect("[", f"'[Statement, Weight]' in the {kind.value} list")
            term = self.expression()
            self.expect(",", "',' and a weight after the statement")
            weight_token = tokens[self.index]
            if not weight_token.isdigit():
                raise self.error("a whole-number weight (0 for plain statements)")
            self.index += 1
            self.expect("]", "']' after the weight")
            try:
                statement = statement_from_term(term, int(weight_token))
            except TermShapeError as shape:
                raise self.error(
                    str(shape), index=entry_at + 1, found=_snippet(self, entry_at)
                ) from None
            self.statement_at[(owner, kind, len(result))] = entry_at
            result.append(statement)
            if tokens[self.index] != ",":
                break
            self.index += 1
        self.expect("]", f"',' or ']' closing the {kind.value} list")
        return result

    def raise_problem(self, problem: coherence.Problem) -> None:
        """Raise the coherence problem at the place in the text it comes from."""
        index = self.class_at.get(problem.entity, self.individual_at.get(problem.entity))
        if problem.field == "mother":
            index = self.mother_at.get(problem.entity, index)
        if problem.kind is not None and problem.position is not None:
            index = self.statement_at.get((problem.entity, problem.kind, problem.position), index)
        if index is None:
            raise KnowledgeError(f"{self.source}: {problem.message}")
        line, column = self.position(index)
        raise KnowledgeError(f"{self.source}, line {line}, column {column}: {problem.message}")


def _snippet(parser: TermParser, start: int) -> str:
    depth = 0
    parts = []
    for token in parser.tokens[start : start + 40]:
        parts.append(token)
        depth += token in "[(" and token != ""
        depth -= token in "])" and token != ""
        if depth == 0:
            break
    return "'" + "".join(parts) + "'"


def read_kb_text(text: str, source: str = "<text>") -> Taxonomy:
    """Parse KB text and check it is coherent; errors name line and column."""
    parser = _KBParser(text, source)
    taxonomy = parser.knowledge_base()
    found = coherence.problems(taxonomy)
    if found:
        parser.raise_problem(found[0])
    return taxonomy


def kb_warnings(path: str | Path) -> list[str]:
    """Statements of a KB file the reasoner ignores (see ``coherence``), with line and column."""
    path = Path(path)
    parser = _KBParser(read_kb_file_text(path), str(path))
    taxonomy = parser.knowledge_base()
    messages = []
    for problem in coherence.warnings(taxonomy):
        index = None
        if problem.kind is not None and problem.position is not None:
            index = parser.statement_at.get((problem.entity, problem.kind, problem.position))
        if index is None:
            messages.append(f"{path}: {problem.message}")
            continue
        line, column = parser.position(index)
        messages.append(f"{path}, line {line}, column {column}: {problem.message}")
    return messages


def read_kb_file_text(path: Path) -> str:
    """The text of a KB file (either form); unreadable, non-UTF-8 or oversized files are KB
    errors."""
    return read_text_file(path, KnowledgeError, "text", "KB file")


def read_kb(path: str | Path) -> Taxonomy:
    """Read a KB file in the paper's syntax."""
    path = Path(path)
    return read_kb_text(read_kb_file_text(path), str(path))


def write_kb_text(taxonomy: Taxonomy) -> str:
    """The KB in the paper's syntax; ``read_kb_text`` reads it back unchanged."""
    rows = []
    for node in taxonomy.classes.values():
        mother = _NONE if node.mother is None else format_atom(node.mother)
        head = f"class({format_atom(node.name)},{mother},{_entries(node.properties)},"
        head += _entries(node.relations) + ",["
        members = [_individual(taxonomy.individuals[name]) for name in node.individuals]
        if members:
            head += "\n  " + ",\n  ".join(members) + "\n"
        rows.append(head + "])")
    if not rows:
        return "[]\n"
    return "[\n" + ",\n".join(rows) + "\n]\n"


def _entries(statements: list[Statement]) -> str:
    return "[" + ",".join(format_entry(s) for s in statements) + "]"


def _individual(node: IndividualNode) -> str:
    return f"[id=>{format_atom(node.name)},{_entries(node.properties)},{_entries(node.relations)}]"


def write_kb(taxonomy: Taxonomy, path: str | Path) -> None:
    """Write a KB file in the paper's syntax."""
    Path(path).write_text(write_kb_text(taxonomy), encoding="utf-8")
