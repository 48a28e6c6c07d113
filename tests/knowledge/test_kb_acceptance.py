"""The benchmark KB of ../shared/tools/kb_generator.py: it loads and its answers are exact."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from kb_strategies import KB_GENERATOR, needs_shared

from homebot.knowledge import KnowledgeBase, read_kb
from homebot.knowledge.closure import Closure
from homebot.knowledge.tables import NAMESPACES

pytestmark = [pytest.mark.acceptance, needs_shared]


@pytest.fixture(scope="module")
def generated(tmp_path_factory: pytest.TempPathFactory) -> tuple[KnowledgeBase, str]:
    directory = tmp_path_factory.mktemp("kb")
    out = directory / "kb"
    subprocess.run(
        [sys.executable, str(KB_GENERATOR), "--out", str(out), "--individuals", "2000"],
        check=True,
        capture_output=True,
    )
    queries = Path(f"{out}_queries.pl").read_text()
    return KnowledgeBase(read_kb(f"{out}.txt")), queries


def test_the_generated_kb_loads(generated: tuple[KnowledgeBase, str]) -> None:
    kb, queries = generated
    stats = dict(re.findall(r"stats\((\w+),(\d+)\)", queries))
    assert len(kb.taxonomy.classes) == int(stats["classes"])
    assert len(kb.taxonomy.individuals) == int(stats["individuals"])
    assert len(kb.class_extension("top")) == int(stats["individuals"])


def test_shared_class_answers_match_a_fresh_evaluation(
    generated: tuple[KnowledgeBase, str],
) -> None:
    kb, queries = generated
    for individual in re.findall(r"q_props\((\w+)\)", queries)[:300]:
        node = kb.taxonomy.individuals[individual]
        fresh = Closure(individual, kb.reasoner.table(node.class_name),
                        (node.properties, node.relations))
        for namespace in NAMESPACES:
            assert kb.holding(individual, namespace) == list(fresh.holding(namespace))


def test_property_extension_agrees_with_each_value(generated: tuple[KnowledgeBase, str]) -> None:
    kb, queries = generated
    prop = re.search(r"q_propext\((\w+)\)", queries).group(1)  # type: ignore[union-attr]
    extension = dict(kb.property_extension(prop))
    for individual in kb.class_extension("top")[:500]:
        assert extension.get(individual, "unknown") == kb.value(individual, prop)


def test_explanations_answer_for_the_query_sample(generated: tuple[KnowledgeBase, str]) -> None:
    kb, queries = generated
    explained = re.findall(r"q_expl\((\w+)\)", queries)
    assert any(kb.explanation_of_individual(i) for i in explained)
