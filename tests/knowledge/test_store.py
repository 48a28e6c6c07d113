"""The SQLite store: updates persist with their log; a killed process loses nothing committed."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from kb_strategies import DATA_KB

from homebot.errors import KnowledgeError
from homebot.knowledge import (
    AddIndividual,
    AddStatement,
    ChangeValue,
    Kind,
    KnowledgeBase,
    RemoveClass,
    Rename,
    Update,
    parse_statement,
    read_kb,
)
from homebot.knowledge.store import KnowledgeStore


def test_a_store_reloads_as_it_was_with_its_log(tmp_path: Path) -> None:
    path = tmp_path / "butler.db"
    with KnowledgeStore.create(path, read_kb(DATA_KB / "butler.kb"), when=0.0) as store:
        store.apply(
            AddStatement(owner="user", kind=Kind.PROPERTY, statement=parse_statement("bad_day")),
            when=10.0,
            why="the user said he had a bad day",
        )
        store.apply(
            ChangeValue(
                owner="noodles",
                kind=Kind.PROPERTY,
                statement=parse_statement("last_seen=>shelf_snacks"),
            ),
            when=20.5,
            why="seen on the shelf of snacks",
        )
        store.apply(AddIndividual(name="tea", class_name="drink"), when=30.0, why="bought")
        store.apply(RemoveClass(name="comestible"), when=40.0, why="flatter hierarchy")
        store.apply(Rename(name="coke", new_name="cola"), when=50.0, why="the user says cola")
        expected = store.kb.taxonomy.copy()
    with KnowledgeStore.open(path) as reopened:
        assert reopened.kb.taxonomy == expected
        assert reopened.kb.value("noodles", "loc") == "shelf_snacks"
        assert reopened.kb.value("user", "tired") == "yes"
        log = reopened.history()
    assert [entry.seq for entry in log] == [1, 2, 3, 4, 5, 6]
    assert log[0].what["type"] == "create"
    assert log[2].when == 20.5
    assert log[2].why == "seen on the shelf of snacks"
    assert log[2].what == {
        "type": "change_value",
        "owner": "noodles",
        "kind": "property",
        "statement": "last_seen=>shelf_snacks",
    }


def test_the_store_can_be_loaded_as_a_kb_file(tmp_path: Path) -> None:
    path = tmp_path / "animals.db"
    KnowledgeStore.create(path, read_kb(DATA_KB / "animals.kb"), when=0.0).close()
    assert KnowledgeBase.load(path).value("pete", "live") == "mexico"


def test_a_refused_update_is_neither_applied_nor_logged(tmp_path: Path) -> None:
    path = tmp_path / "kb.db"
    with KnowledgeStore.create(path, read_kb(DATA_KB / "animals.kb"), when=0.0) as store:
        with pytest.raises(KnowledgeError):
            store.apply(AddIndividual(name="pete", class_name="birds"), when=1.0, why="twice")
        with pytest.raises(KnowledgeError, match="why"):
            store.apply(AddIndividual(name="tweety", class_name="birds"), when=1.0, why=" ")
        assert len(store.history()) == 1


def test_store_errors_are_knowledge_errors(tmp_path: Path) -> None:
    with pytest.raises(KnowledgeError, match="no knowledge store"):
        KnowledgeStore.open(tmp_path / "missing.db")
    junk = tmp_path / "junk.db"
    junk.write_text("this is not a database")
    with pytest.raises(KnowledgeError):
        KnowledgeStore.open(junk)
    taxonomy = read_kb(DATA_KB / "animals.kb")
    KnowledgeStore.create(tmp_path / "kb.db", taxonomy, when=0.0).close()
    with pytest.raises(KnowledgeError, match="exists already"):
        KnowledgeStore.create(tmp_path / "kb.db", taxonomy, when=0.0)


def test_another_programs_database_is_refused_and_left_as_it_was(tmp_path: Path) -> None:
    other = tmp_path / "other.db"
    connection = sqlite3.connect(other)
    connection.execute("CREATE TABLE t (x)")
    connection.execute("INSERT INTO t VALUES (1)")
    connection.commit()
    connection.close()
    with pytest.raises(KnowledgeError, match="not a homebot knowledge store"):
        KnowledgeStore.open(other)
    connection = sqlite3.connect(other)
    assert connection.execute("PRAGMA journal_mode").fetchone() == ("delete",)
    assert connection.execute("SELECT x FROM t").fetchall() == [(1,)]
    connection.close()


_WRITER = textwrap.dedent(
    """
    import sys
    from homebot.knowledge import AddIndividual, AddStatement, Kind, Literal
    from homebot.knowledge.store import KnowledgeStore

    store = KnowledgeStore.open(sys.argv[1])
    for n in range(100000):
        store.apply(AddIndividual(name=f"bird{n}", class_name="birds"), when=float(n), why="seen")
        seq = store.apply(
            AddStatement(owner=f"bird{n}", kind=Kind.PROPERTY, statement=Literal("ringed", n)),
            when=float(n),
            why="ringed",
        )
        print(n, seq, flush=True)
    """
)


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="needs SIGKILL")
def test_a_killed_process_loses_no_committed_update(tmp_path: Path) -> None:
    path = tmp_path / "kb.db"
    KnowledgeStore.create(path, read_kb(DATA_KB / "animals.kb"), when=0.0).close()
    script = tmp_path / "writer.py"
    script.write_text(_WRITER)
    process = subprocess.Popen(
        [sys.executable, str(script), str(path)], stdout=subprocess.PIPE, text=True
    )
    assert process.stdout is not None
    reported = []
    for line in process.stdout:
        reported.append(tuple(int(part) for part in line.split()))
        if len(reported) >= 40:
            break
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    with KnowledgeStore.open(path) as store:
        log = store.history()
        committed = {entry.seq for entry in log}
        for n, seq in reported:  # everything the writer saw committed is there
            assert seq in committed
            assert store.kb.value(f"bird{n}", "ringed") == n
        # and the KB is exactly the replay of its log
        replayed = KnowledgeBase(read_kb(DATA_KB / "animals.kb"))
        for entry in log[1:]:
            replayed.apply(Update.from_dict(entry.what))
        assert replayed.taxonomy == store.kb.taxonomy
