"""Golem-III's non-monotonic knowledge base: classes, defaults, preferences and abduction."""

from homebot.knowledge.abduction import Explanation
from homebot.knowledge.knowledge_base import UNKNOWN, Answer, KnowledgeBase
from homebot.knowledge.model import (
    ANY,
    TOP,
    ClassNode,
    IndividualNode,
    Kind,
    Literal,
    Preference,
    Statement,
    Taxonomy,
    Value,
)
from homebot.knowledge.reasoner import Touched
from homebot.knowledge.syntax import read_kb, read_kb_text, write_kb, write_kb_text
from homebot.knowledge.terms import parse_statement
from homebot.knowledge.updates import (
    AddClass,
    AddIndividual,
    AddStatement,
    ChangeValue,
    ChangeWeight,
    MoveClass,
    MoveIndividual,
    RemoveClass,
    RemoveIndividual,
    RemoveStatement,
    Rename,
    Update,
)
from homebot.knowledge.yaml_form import (
    read_kb_yaml,
    read_kb_yaml_text,
    write_kb_yaml,
    write_kb_yaml_text,
)

__all__ = [
    "ANY",
    "TOP",
    "UNKNOWN",
    "AddClass",
    "AddIndividual",
    "AddStatement",
    "Answer",
    "ChangeValue",
    "ChangeWeight",
    "ClassNode",
    "Explanation",
    "IndividualNode",
    "Kind",
    "KnowledgeBase",
    "Literal",
    "MoveClass",
    "MoveIndividual",
    "Preference",
    "RemoveClass",
    "RemoveIndividual",
    "RemoveStatement",
    "Rename",
    "Statement",
    "Taxonomy",
    "Touched",
    "Update",
    "Value",
    "parse_statement",
    "read_kb",
    "read_kb_text",
    "read_kb_yaml",
    "read_kb_yaml_text",
    "write_kb",
    "write_kb_text",
    "write_kb_yaml",
    "write_kb_yaml_text",
]
