"""A KB persisted in SQLite: one row per class, individual and statement, and a log of updates.

Every update is one transaction that rewrites the rows of what it touched and appends
to the log what was done, when (simulated time, given by the caller) and why. The
database runs in WAL mode with ``synchronous=FULL``, so a committed update survives a
killed process (and a power cut); an update interrupted before its commit leaves no
trace. Reopening the store rebuilds the KB exactly as it was.
"""

from __future__ import annotations

import json
import sqlite3
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import Any

from homebot.errors import KnowledgeError
from homebot.knowledge.knowledge_base import KnowledgeBase
from homebot.knowledge.model import ClassNode, IndividualNode, Kind, Preference, Taxonomy
from homebot.knowledge.reasoner import Touched
from homebot.knowledge.terms import format_statement, parse_statement
from homebot.knowledge.updates import Update

__all__ = ["KnowledgeStore", "LogEntry"]

_SCHEMA_VERSION = 1
_SCHEMA = """
CREATE TABLE classes (name TEXT PRIMARY KEY, mother TEXT, position INTEGER NOT NULL);
CREATE TABLE individuals (
    name TEXT PRIMARY KEY, class TEXT NOT NULL, position INTEGER NOT NULL
);
CREATE TABLE statements (
    owner TEXT NOT NULL, kind TEXT NOT NULL, position INTEGER NOT NULL,
    text TEXT NOT NULL, weight INTEGER NOT NULL,
    PRIMARY KEY (owner, kind, position)
);
CREATE TABLE updates (
    seq INTEGER PRIMARY KEY AUTOINCREMENT, at REAL NOT NULL, what TEXT NOT NULL,
    why TEXT NOT NULL
);
"""


@dataclass(frozen=True, slots=True)
class LogEntry:
    """One logged update: its sequence number, simulated time, description and reason."""

    seq: int
    when: float
    what: dict[str, Any]
    why: str


class KnowledgeStore:
    """A ``KnowledgeBase`` kept in a SQLite file; use ``create`` or ``open``."""

    __slots__ = ("_connection", "kb", "path")

    def __init__(self, path: Path, connection: sqlite3.Connection, kb: KnowledgeBase) -> None:
        self.path = path
        self._connection = connection
        self.kb = kb

    # -- opening ---------------------------------------------------------------------------

    @classmethod
    def create(
        cls, path: str | Path, taxonomy: Taxonomy, *, when: float, why: str = "created"
    ) -> KnowledgeStore:
        """Make a new store holding ``taxonomy``; the file must not exist yet."""
        path = Path(path)
        if path.exists():
            raise KnowledgeError(f"{path} exists already; open it, or choose another file")
        kb = KnowledgeBase(taxonomy)
        connection = _connect(path)
        with _transaction(connection):
            for statement in _SCHEMA.strip().split(";\n"):
                connection.execute(statement)
            connection.execute(f"PRAGMA user_version = {_SCHEMA_VERSION}")
            _write_all(connection, taxonomy)
            literals, preferences = taxonomy.statement_count()
            _log(
                connection,
                when,
                {
                    "type": "create",
                    "classes": len(taxonomy.classes),
                    "individuals": len(taxonomy.individuals),
                    "literals": literals,
                    "preferences": preferences,
                },
                why,
            )
        return cls(path, connection, kb)

    @classmethod
    def open(cls, path: str | Path) -> KnowledgeStore:
        """Open an existing store and rebuild its KB."""
        path = Path(path)
        if not path.is_file():
            raise KnowledgeError(f"no knowledge store at {path}; create one first")
        connection = _connect(path, store=True)
        try:
            kb = KnowledgeBase(_read_all(connection, str(path)))
        except (KnowledgeError, sqlite3.DatabaseError) as error:
            connection.close()
            if isinstance(error, KnowledgeError):
                raise
            raise KnowledgeError(f"{path} is not a readable knowledge store: {error}") from None
        return cls(path, connection, kb)

    def close(self) -> None:
        """Close the database (everything committed is already on disk)."""
        self._connection.close()

    def __enter__(self) -> KnowledgeStore:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        self.close()

    # -- updating ------------------------------------------------------------------------------

    def apply(self, update: Update, *, when: float, why: str) -> int:
        """Apply and persist one update in one transaction; returns its log sequence number."""
        if not why.strip():
            raise KnowledgeError("say why the KB is updated (why=...)")
        touched = self.kb.apply(update)
        try:
            with _transaction(self._connection):
                _write_touched(self._connection, self.kb.taxonomy, touched)
                seq = _log(self._connection, when, update.to_dict(), why)
        except sqlite3.Error as error:
            self.kb = KnowledgeBase(_read_all(self._connection, str(self.path)))
            raise KnowledgeError(f"could not save the update to {self.path}: {error}") from None
        return seq

    def history(self) -> list[LogEntry]:
        """Every logged update, oldest first."""
        rows = self._connection.execute("SELECT seq, at, what, why FROM updates ORDER BY seq")
        return [LogEntry(seq, at, json.loads(what), why) for seq, at, what, why in rows]


def _connect(path: Path, *, store: bool = False) -> sqlite3.Connection:
    """Connect; with ``store``, first check the file is a store (nothing else is changed)."""
    try:
        connection = sqlite3.connect(path, isolation_level=None)
        version = connection.execute("PRAGMA user_version").fetchone()[0]
        if store and version != _SCHEMA_VERSION:
            connection.close()
            raise KnowledgeError(f"{path} is not a homebot knowledge store (version {version})")
        connection.execute("PRAGMA journal_mode = WAL")
        connection.execute("PRAGMA synchronous = FULL")
    except sqlite3.Error as error:
        raise KnowledgeError(f"cannot open knowledge store {path}: {error}") from None
    return connection


class _transaction:
    """``BEGIN IMMEDIATE`` ... ``COMMIT``, or ``ROLLBACK`` on any error."""

    def __init__(self, connection: sqlite3.Connection) -> None:
        self.connection = connection

    def __enter__(self) -> None:
        self.connection.execute("BEGIN IMMEDIATE")

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        trace: TracebackType | None,
    ) -> None:
        self.connection.execute("COMMIT" if kind is None else "ROLLBACK")


def _log(connection: sqlite3.Connection, when: float, what: dict[str, Any], why: str) -> int:
    cursor = connection.execute(
        "INSERT INTO updates (at, what, why) VALUES (?, ?, ?)",
        (float(when), json.dumps(what, sort_keys=True), why),
    )
    return int(cursor.lastrowid or 0)


def _write_all(connection: sqlite3.Connection, taxonomy: Taxonomy) -> None:
    connection.executemany(
        "INSERT INTO classes VALUES (?, ?, ?)",
        ((c.name, c.mother, i) for i, c in enumerate(taxonomy.classes.values())),
    )
    connection.executemany(
        "INSERT INTO individuals VALUES (?, ?, ?)",
        (
            (name, c.name, i)
            for c in taxonomy.classes.values()
            for i, name in enumerate(c.individuals)
        ),
    )
    for entity in taxonomy.entities():
        _write_statements(connection, entity)


def _write_statements(connection: sqlite3.Connection, entity: ClassNode | IndividualNode) -> None:
    connection.executemany(
        "INSERT INTO statements VALUES (?, ?, ?, ?, ?)",
        (
            (
                entity.name,
                kind.value,
                position,
                format_statement(statement),
                statement.weight if isinstance(statement, Preference) else 0,
            )
            for kind in Kind
            for position, statement in enumerate(entity.statements(kind))
        ),
    )


def _write_touched(connection: sqlite3.Connection, taxonomy: Taxonomy, touched: Touched) -> None:
    """Rewrite the rows of every touched name; renumber only where membership changed."""
    names = touched.classes | touched.individuals | touched.membership
    reorder_classes = touched.structure
    reorder_members = {n for n in touched.membership if n in taxonomy.classes}
    for name in sorted(names):
        old_class = connection.execute(
            "SELECT position FROM classes WHERE name = ?", (name,)
        ).fetchone()
        old_individual = connection.execute(
            "SELECT class, position FROM individuals WHERE name = ?", (name,)
        ).fetchone()
        connection.execute("DELETE FROM classes WHERE name = ?", (name,))
        connection.execute("DELETE FROM individuals WHERE name = ?", (name,))
        connection.execute("DELETE FROM statements WHERE owner = ?", (name,))
        node = taxonomy.classes.get(name)
        if node is not None:
            reorder_classes = reorder_classes or old_class is None
            position = old_class[0] if old_class else 0
            connection.execute(
                "INSERT INTO classes VALUES (?, ?, ?)", (name, node.mother, position)
            )
            _write_statements(connection, node)
        individual = taxonomy.individuals.get(name)
        if individual is not None:
            position = 0
            if old_individual and old_individual[0] == individual.class_name:
                position = old_individual[1]
            else:
                reorder_members.add(individual.class_name)
            connection.execute(
                "INSERT INTO individuals VALUES (?, ?, ?)",
                (name, individual.class_name, position),
            )
            _write_statements(connection, individual)
    if reorder_classes:
        connection.executemany(
            "UPDATE classes SET position = ? WHERE name = ?",
            ((i, name) for i, name in enumerate(taxonomy.classes)),
        )
    for owner in sorted(reorder_members):
        connection.executemany(
            "UPDATE individuals SET position = ? WHERE name = ?",
            ((i, name) for i, name in enumerate(taxonomy.classes[owner].individuals)),
        )


def _read_all(connection: sqlite3.Connection, source: str) -> Taxonomy:
    taxonomy = Taxonomy()
    for name, mother, _ in connection.execute("SELECT * FROM classes ORDER BY position"):
        taxonomy.classes[name] = ClassNode(name, mother)
    for name, class_name, _ in connection.execute(
        "SELECT * FROM individuals ORDER BY class, position"
    ):
        node = taxonomy.classes.get(class_name)
        if node is None:
            raise KnowledgeError(f"{source}: individual '{name}' has no class '{class_name}'")
        taxonomy.individuals[name] = IndividualNode(name, class_name)
        node.individuals.append(name)
    rows = connection.execute(
        "SELECT owner, kind, text, weight FROM statements ORDER BY owner, kind, position"
    )
    for owner, kind, text, weight in rows:
        entity = taxonomy.classes.get(owner) or taxonomy.individuals.get(owner)
        if entity is None:
            raise KnowledgeError(f"{source}: statements of unknown '{owner}'")
        entity.statements(Kind(kind)).append(parse_statement(text, weight, source))
    return _in_declaration_order(taxonomy)


def _in_declaration_order(taxonomy: Taxonomy) -> Taxonomy:
    """Individuals were read grouped by class; list them in class order like a file does."""
    ordered = Taxonomy()
    ordered.classes = taxonomy.classes
    for node in taxonomy.classes.values():
        for name in node.individuals:
            ordered.individuals[name] = taxonomy.individuals[name]
    return ordered
