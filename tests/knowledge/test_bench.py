"""The kb benchmark runs and reports its figures (timings are printed, never asserted)."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest
from kb_strategies import SHARED, needs_shared
from rich.console import Console

from homebot.bench import kb as bench
from homebot.knowledge import KnowledgeBase, read_kb_text


def _arguments(**overrides: object) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    bench.add_arguments(parser)
    args = parser.parse_args(["--chains", "5,10", "--repeat", "1"])
    for key, value in overrides.items():
        setattr(args, key, value)
    return args


def test_chain_kbs_reach_their_last_link() -> None:
    kb = KnowledgeBase(read_kb_text(bench.chain_kb_text(12)))
    assert kb.value("x", "d12") == "yes"


def test_without_shared_the_generated_part_is_skipped(tmp_path: Path) -> None:
    figures = bench.run(_arguments(shared=tmp_path), Console(quiet=True))
    assert set(figures["chained_defaults"]) == {"5", "10"}
    assert figures["generated"].startswith("skipped")


@pytest.mark.acceptance
@needs_shared
def test_the_generated_part_reports_every_figure() -> None:
    figures = bench.run(_arguments(shared=SHARED, individuals=500), Console(quiet=True))
    generated = figures["generated"]
    assert generated["individuals"] == 500
    assert {"properties_of_individual", "property_extension", "updates"} <= set(generated)
    assert generated["updates"]["individual last_seen"]["dropped"] == 1
