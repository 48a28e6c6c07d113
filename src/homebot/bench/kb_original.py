"""KB fidelity: our answers beside SitLog's own KB service under SWI-Prolog, on one KB.

The comparison harness of issue 13. When ``swipl`` is on the PATH and a SitLog checkout
is given (``--sitlog DIR`` or ``$SITLOG_HOME``; its ``knowledge_base/
change_KB_extensions.pl`` is the original service, GPL, run as it is and never copied),
a KB made by ``../shared/tools/kb_generator.py`` is answered by both, and the
``properties_of_individual`` answers are counted: identical, the same literals in
another order, or different. The times of both come from this same run. Without either,
the benchmark says what is missing and measures nothing.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from rich.console import Console

from homebot.bench.arguments import count
from homebot.knowledge import KnowledgeBase, read_kb
from homebot.knowledge.terms import format_literal

__all__ = ["add_arguments", "compare_answers", "run", "split_prolog_list"]

# Our own driver for the original service: load its clauses without running its
# directives (they consult the rest of the inference cycle), read the KB file as SitLog's
# open_kb does, answer every q_props(Id) of the workload, one line each.
DRIVER = r"""
:- op(800, xfx, =>>).
:- op(700, xfx, =>).
:- use_module(library(time)).
:- dynamic q_props/1, q_expl/1, q_propext/1, stats/2.

homebot_load(File) :-
    open(File, read, S),
    repeat,
    read_term(S, T, []),
    (   T == end_of_file -> !, close(S)
    ;   (T = (:- _) -> true ; assertz(T)), fail
    ).

homebot_kb(File, KB) :-
    read_file_to_string(File, Text, []),
    string_concat(Text, " .", Full),
    term_string(KB, Full).

homebot_answer(KB, Limit, Id) :-
    (   catch(call_with_time_limit(Limit, properties_of_individual(Id, KB, P)), E,
              (P = error(E)))
    ->  true
    ;   P = failed
    ),
    format("~w\t~q~n", [Id, P]).

homebot_main :-
    current_prolog_flag(argv, [Service, KBFile, Queries, LimitText]),
    atom_number(LimitText, Limit),
    homebot_load(Service),
    consult(Queries),
    homebot_kb(KBFile, KB),
    get_time(Began),
    forall(q_props(Id), homebot_answer(KB, Limit, Id)),
    get_time(Ended),
    Seconds is Ended - Began,
    format(user_error, "seconds ~w~n", [Seconds]),
    halt.
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--sitlog", type=Path, default=None,
                        help="a SitLog checkout (default: $SITLOG_HOME)")
    parser.add_argument("--individuals", type=count("--individuals", 1, 1_000_000),
                        default=10_000, help="individuals in the generated KB (default 10000)")
    parser.add_argument("--queries", type=count("--queries", 1, 100_000), default=2000,
                        help="individuals asked (default 2000, the generator's workload)")
    parser.add_argument("--time-limit", type=count("--time-limit", 1, 3600), default=10,
                        help="seconds the original may take per query (default 10)")
    parser.add_argument("--shared", type=Path, default=None,
                        help="the shared acceptance directory (default: ../shared of the repo)")


def split_prolog_list(text: str) -> list[str] | None:
    """The top-level elements of a Prolog list as written by ``~q``; None if not a list."""
    text = text.strip()
    if not (text.startswith("[") and text.endswith("]")):
        return None
    items: list[str] = []
    depth = 0
    current = ""
    quoted = False
    for character in text[1:-1]:
        if character == "'":
            quoted = not quoted
        elif not quoted and character in "([":
            depth += 1
        elif not quoted and character in ")]":
            depth -= 1
        if character == "," and depth == 0 and not quoted:
            items.append(current)
            current = ""
        else:
            current += character
    if current:
        items.append(current)
    return items


def compare_answers(kb: KnowledgeBase, original: dict[str, str]) -> dict[str, Any]:
    """Count our answers against the original's: identical, reordered, different."""
    identical = reordered = different = failed = 0
    examples: list[dict[str, Any]] = []
    for individual, answer in original.items():
        theirs = split_prolog_list(answer)
        ours = [format_literal(literal) for literal in kb.properties_of_individual(individual)]
        if theirs is None:
            failed += 1
        elif theirs == ours:
            identical += 1
        elif sorted(theirs) == sorted(ours):
            reordered += 1
        else:
            different += 1
            if len(examples) < 5:
                examples.append({"individual": individual,
                                 "only_original": sorted(set(theirs) - set(ours)),
                                 "only_homebot": sorted(set(ours) - set(theirs))})
    return {"answers": len(original), "identical": identical,
            "same_literals_other_order": reordered, "different": different,
            "original_failed_or_timed_out": failed, "examples_of_differences": examples}


def _missing(args: argparse.Namespace) -> tuple[str | None, Path | None, Path | None]:
    swipl = shutil.which("swipl")
    home = args.sitlog or (Path(os.environ["SITLOG_HOME"]) if "SITLOG_HOME" in os.environ
                           else None)
    service = home / "knowledge_base" / "change_KB_extensions.pl" if home else None
    shared = args.shared or Path(__file__).resolve().parents[3] / ".." / "shared"
    generator = shared / "tools" / "kb_generator.py"
    if swipl is None:
        return "skipped: swipl (SWI-Prolog) is not on the PATH", None, None
    if service is None or not service.is_file():
        return ("skipped: no SitLog checkout (give --sitlog DIR or set SITLOG_HOME; it needs "
                "knowledge_base/change_KB_extensions.pl)"), None, None
    if not generator.is_file():
        return "skipped: ../shared/tools/kb_generator.py not found", None, None
    return None, service, generator


def run(args: argparse.Namespace, console: Console | None = None) -> dict[str, Any]:
    """Answer one generated KB with both; count agreements. Never asserts anything."""
    reason, service, generator = _missing(args)
    if reason is not None or service is None or generator is None:
        if console is not None:
            console.print(f"[yellow]kb_original {reason}[/]")
        return {"benchmark": "kb_original", "skipped": reason}
    with tempfile.TemporaryDirectory(prefix="homebot-kb-original-") as temporary:
        folder = Path(temporary)
        subprocess.run([sys.executable, str(generator), "--out", str(folder / "kb"),
                        "--individuals", str(args.individuals), "--nprops", str(args.queries)],
                       check=True, capture_output=True, text=True)
        (folder / "driver.pl").write_text(DRIVER, encoding="utf-8")
        began = time.perf_counter()
        done = subprocess.run(
            ["swipl", "-q", "-g", "homebot_main", str(folder / "driver.pl"), "--",
             str(service), str(folder / "kb.txt"), str(folder / "kb_queries.pl"),
             str(args.time_limit)], capture_output=True, text=True, check=False)
        prolog_wall = time.perf_counter() - began
        original = dict(line.split("\t", 1) for line in done.stdout.splitlines()
                        if "\t" in line)
        found = re.search(r"seconds ([0-9.e+-]+)", done.stderr)
        prolog_seconds = float(found.group(1)) if found else None
        kb = KnowledgeBase(read_kb(folder / "kb.txt"))
        began = time.perf_counter()
        for individual in original:
            kb.properties_of_individual(individual)
        ours_seconds = time.perf_counter() - began
    figures = compare_answers(kb, original)
    figures.update(
        benchmark="kb_original", individuals=args.individuals,
        original_seconds_for_all_queries=None if prolog_seconds is None else round(
            prolog_seconds, 3),
        original_process_wall_s=round(prolog_wall, 2),
        homebot_seconds_for_all_queries_first_pass=round(ours_seconds, 4))
    if prolog_seconds:
        figures["ratio_measured_in_this_run"] = round(prolog_seconds / max(ours_seconds, 1e-9), 1)
    if console is not None:
        console.print(
            f"[bold]KB fidelity[/] ({figures['answers']} properties_of_individual answers, "
            f"{args.individuals}-individual generated KB): {figures['identical']} identical, "
            f"{figures['same_literals_other_order']} the same literals in another order, "
            f"{figures['different']} different, {figures['original_failed_or_timed_out']} "
            "failed or timed out in the original")
        if prolog_seconds:
            console.print(f"  times in this run: SitLog under SWI-Prolog {prolog_seconds:.2f} s, "
                          f"homebot (first pass, cold) {ours_seconds:.3f} s")
        for example in figures["examples_of_differences"]:
            console.print(f"  differs: {example}", highlight=False)
    return figures
