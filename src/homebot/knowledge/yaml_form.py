"""The KB in YAML: classes with their statements and individuals; errors name line and column.

Schema::

    classes:
      - name: birds
        mother: animals            # none (or omitted) for top only
        properties:                # a string is a weight-0 literal in KB syntax
          - fly
          - not(swim)
          - {statement: "work=>'-'=>>live=>'-'", weight: 3}
        relations: [...]
        individuals:
          - name: pete
            properties: [size=>large]
            relations: [work=>mexico]
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from homebot.errors import KnowledgeError
from homebot.knowledge import coherence
from homebot.knowledge.model import (
    ANY,
    ClassNode,
    IndividualNode,
    Kind,
    Preference,
    Statement,
    Taxonomy,
)
from homebot.knowledge.syntax import read_kb_file_text
from homebot.knowledge.terms import format_statement, parse_statement
from homebot.yamlfile import compose_yaml_text

__all__ = ["read_kb_yaml", "read_kb_yaml_text", "write_kb_yaml", "write_kb_yaml_text"]

_Mark = tuple[int, int]
_NULL_TAG = "tag:yaml.org,2002:null"


class _YamlReader:
    """Walks composed YAML nodes, so every error can name a line and a column."""

    def __init__(self, text: str, source: str) -> None:
        self.source = source
        self.text = text
        self.where: dict[tuple[str, Kind | None, int | None, str | None], _Mark] = {}

    def fail(self, node: yaml.Node | None, message: str) -> KnowledgeError:
        if node is None:
            return KnowledgeError(f"{self.source}: {message}")
        mark = node.start_mark
        return KnowledgeError(
            f"{self.source}, line {mark.line + 1}, column {mark.column + 1}: {message}"
        )

    def mapping(self, node: yaml.Node, what: str, allowed: set[str]) -> dict[str, yaml.Node]:
        if not isinstance(node, yaml.MappingNode):
            raise self.fail(node, f"expected {what} (a mapping), found {_describe(node)}")
        result: dict[str, yaml.Node] = {}
        for key_node, value_node in node.value:
            key = key_node.value if isinstance(key_node, yaml.ScalarNode) else None
            if key not in allowed:
                expected = ", ".join(sorted(allowed))
                raise self.fail(key_node, f"expected one of the keys {expected}, found {key!r}")
            if key in result:
                raise self.fail(key_node, f"expected each key once, found {key!r} again")
            result[key] = value_node
        return result

    def sequence(self, node: yaml.Node | None, what: str) -> list[yaml.Node]:
        if node is None or (isinstance(node, yaml.ScalarNode) and node.value in ("", "~")):
            return []
        if not isinstance(node, yaml.SequenceNode):
            raise self.fail(node, f"expected {what} (a list), found {_describe(node)}")
        return list(node.value)

    def name(self, node: yaml.Node | None, what: str, parent: yaml.Node) -> str:
        if node is None:
            raise self.fail(parent, f"expected {what}")
        if (
            not isinstance(node, yaml.ScalarNode)
            or node.value in ("", ANY)
            or node.tag == _NULL_TAG
        ):
            raise self.fail(node, f"expected {what}, found {_describe(node)}")
        return str(node.value)

    def read(self) -> Taxonomy:
        root = compose_yaml_text(self.text, self.source, KnowledgeError)
        if root is None:
            raise KnowledgeError(f"{self.source}: expected a mapping with 'classes', found nothing")
        top = self.mapping(root, "the KB", {"classes"})
        taxonomy = Taxonomy()
        for class_node in self.sequence(top.get("classes"), "the list of classes"):
            self.read_class(taxonomy, class_node)
        found = coherence.problems(taxonomy)
        if found:
            problem = found[0]
            mark = self.where.get((problem.entity, problem.kind, problem.position, problem.field))
            mark = mark or self.where.get((problem.entity, None, None, None))
            if mark is None:
                raise KnowledgeError(f"{self.source}: {problem.message}")
            raise KnowledgeError(
                f"{self.source}, line {mark[0]}, column {mark[1]}: {problem.message}"
            )
        return taxonomy

    def read_class(self, taxonomy: Taxonomy, node: yaml.Node) -> None:
        fields = self.mapping(
            node, "a class", {"name", "mother", "properties", "relations", "individuals"}
        )
        name = self.name(fields.get("name"), "the class name (name: ...)", node)
        if name in taxonomy.classes or name == "none":
            raise self.fail(
                fields["name"], f"expected a class name not used before, found {name!r}"
            )
        self._remember(name, None, None, None, fields["name"])
        mother_node = fields.get("mother")
        mother: str | None = None
        if mother_node is not None and not (
            isinstance(mother_node, yaml.ScalarNode)
            and (mother_node.value == "none" or mother_node.tag == _NULL_TAG)
        ):
            mother = self.name(mother_node, "the mother class", node)
            self._remember(name, None, None, "mother", mother_node)
        klass = ClassNode(name, mother)
        klass.properties = self.statements(name, Kind.PROPERTY, fields.get("properties"))
        klass.relations = self.statements(name, Kind.RELATION, fields.get("relations"))
        taxonomy.classes[name] = klass
        for member in self.sequence(fields.get("individuals"), "the list of individuals"):
            self.read_individual(taxonomy, klass, member)

    def read_individual(self, taxonomy: Taxonomy, klass: ClassNode, node: yaml.Node) -> None:
        fields = self.mapping(node, "an individual", {"name", "properties", "relations"})
        name = self.name(fields.get("name"), "the individual's name (name: ...)", node)
        if name in taxonomy.individuals:
            raise self.fail(fields["name"], f"expected a name not used before, found {name!r}")
        self._remember(name, None, None, None, fields["name"])
        individual = IndividualNode(name, klass.name)
        individual.properties = self.statements(name, Kind.PROPERTY, fields.get("properties"))
        individual.relations = self.statements(name, Kind.RELATION, fields.get("relations"))
        taxonomy.individuals[name] = individual
        klass.individuals.append(name)

    def statements(self, owner: str, kind: Kind, node: yaml.Node | None) -> list[Statement]:
        result = []
        for position, item in enumerate(self.sequence(node, f"the {kind.value} list")):
            weight = 0
            text_node: yaml.Node | None = item
            if isinstance(item, yaml.MappingNode):
                fields = self.mapping(item, "a weighted statement", {"statement", "weight"})
                text_node = fields.get("statement")
                weight_node = fields.get("weight")
                if text_node is None or weight_node is None:
                    raise self.fail(item, "expected both statement: and weight:")
                stated = _scalar(weight_node)
                if isinstance(stated, bool) or not isinstance(stated, int) or stated < 0:
                    raise self.fail(
                        weight_node, f"expected a whole-number weight, found {stated!r}"
                    )
                weight = stated
            if not isinstance(text_node, yaml.ScalarNode):
                raise self.fail(
                    text_node, f"expected a statement in KB syntax, found {_describe(text_node)}"
                )
            mark = text_node.start_mark
            source = f"{self.source}, line {mark.line + 1}, column {mark.column + 1}, statement"
            result.append(parse_statement(str(text_node.value), weight, source))
            self._remember(owner, kind, position, None, item)
        return result

    def _remember(
        self,
        owner: str,
        kind: Kind | None,
        position: int | None,
        field: str | None,
        node: yaml.Node,
    ) -> None:
        self.where[(owner, kind, position, field)] = (
            node.start_mark.line + 1,
            node.start_mark.column + 1,
        )


def _scalar(node: yaml.Node) -> object:
    """The Python value of a scalar node (None for anything else)."""
    if not isinstance(node, yaml.ScalarNode):
        return None
    try:
        return yaml.safe_load(node.value) if node.style is None else node.value
    except (yaml.YAMLError, ValueError):  # ValueError: an integer of over 4300 digits
        return node.value


def _describe(node: yaml.Node | None) -> str:
    if node is None:
        return "nothing"
    if isinstance(node, yaml.ScalarNode):
        return f"{node.value!r}"
    return "a mapping" if isinstance(node, yaml.MappingNode) else "a list"


def read_kb_yaml_text(text: str, source: str = "<yaml>") -> Taxonomy:
    """Parse the YAML form and check coherence."""
    return _YamlReader(text, source).read()


def read_kb_yaml(path: str | Path) -> Taxonomy:
    """Read a KB file in the YAML form."""
    path = Path(path)
    return read_kb_yaml_text(read_kb_file_text(path), str(path))


def _statement_data(statement: Statement) -> Any:
    if isinstance(statement, Preference):
        return {"statement": format_statement(statement), "weight": statement.weight}
    return format_statement(statement)


def write_kb_yaml_text(taxonomy: Taxonomy) -> str:
    """The KB in the YAML form; ``read_kb_yaml_text`` reads it back unchanged."""
    classes = []
    for node in taxonomy.classes.values():
        data: dict[str, Any] = {"name": node.name, "mother": node.mother or "none"}
        data["properties"] = [_statement_data(s) for s in node.properties]
        data["relations"] = [_statement_data(s) for s in node.relations]
        data["individuals"] = [
            {
                "name": member,
                "properties": [_statement_data(s) for s in taxonomy.individuals[member].properties],
                "relations": [_statement_data(s) for s in taxonomy.individuals[member].relations],
            }
            for member in node.individuals
        ]
        classes.append(data)
    return yaml.safe_dump({"classes": classes}, sort_keys=False, allow_unicode=True, width=100)


def write_kb_yaml(taxonomy: Taxonomy, path: str | Path) -> None:
    """Write a KB file in the YAML form."""
    Path(path).write_text(write_kb_yaml_text(taxonomy), encoding="utf-8")
