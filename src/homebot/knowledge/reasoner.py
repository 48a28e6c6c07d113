"""The reasoner's caches: class tables, closures and extensions, dropped only where touched."""

from __future__ import annotations

from dataclasses import dataclass, field

from homebot.knowledge.closure import Closure
from homebot.knowledge.model import Kind, Literal, Taxonomy
from homebot.knowledge.tables import EMPTY, ClassTable, Resolution, effective, resolve_levels

__all__ = ["CacheStatistics", "Reasoner", "Touched"]

_KINDS = (Kind.PROPERTY, Kind.RELATION)


@dataclass(frozen=True, slots=True)
class Touched:
    """What an update changed, so that only the answers depending on it are recomputed.

    ``classes``: classes whose own statements or place in the tree changed (their whole
    subtree inherits the change); ``individuals``: individuals whose own statements
    changed; ``membership``: classes whose set of members changed (with their
    ancestors); ``structure``: whether the tree itself changed shape.
    """

    classes: frozenset[str] = frozenset()
    individuals: frozenset[str] = frozenset()
    membership: frozenset[str] = frozenset()
    structure: bool = False

    def __or__(self, other: Touched) -> Touched:
        return Touched(
            self.classes | other.classes,
            self.individuals | other.individuals,
            self.membership | other.membership,
            self.structure or other.structure,
        )


@dataclass(slots=True)
class CacheStatistics:
    """How much the reasoner built and how much updates threw away."""

    tables_built: int = 0
    closures_built: int = 0
    extensions_built: int = 0
    dropped: int = 0
    last_dropped: int = 0
    by_update: list[int] = field(default_factory=list)


class Reasoner:
    """Builds and caches what queries need over one taxonomy."""

    __slots__ = ("_children", "_closures", "_extensions", "_tables", "statistics", "taxonomy")

    def __init__(self, taxonomy: Taxonomy) -> None:
        self.taxonomy = taxonomy
        self._tables: dict[str, ClassTable] = {}
        self._closures: dict[str, Closure] = {}
        self._extensions: dict[str, tuple[str, ...]] = {}
        self._children: dict[str, list[str]] | None = None
        self.statistics = CacheStatistics()

    # -- building --------------------------------------------------------------------

    def table(self, class_name: str) -> ClassTable:
        """The inherited table of a class (its ancestors' tables are built first)."""
        found = self._tables.get(class_name)
        if found is not None:
            return found
        missing = []
        for ancestor in self.taxonomy.lineage(class_name):
            if ancestor in self._tables:
                break
            missing.append(ancestor)
        for name in reversed(missing):
            node = self.taxonomy.classes[name]
            mother = self._tables.get(node.mother) if node.mother is not None else None
            self._tables[name] = ClassTable(name, node.properties, node.relations, mother)
            self.statistics.tables_built += 1
        return self._tables[class_name]

    def closure(self, name: str) -> Closure:
        """The theory of a class or an individual (``KnowledgeError`` if unknown)."""
        found = self._closures.get(name)
        if found is not None:
            return found
        individual = self.taxonomy.individuals.get(name)
        if individual is None:
            if name not in self.taxonomy.classes:
                self.taxonomy.entity(name)  # raises KnowledgeError with close names
            closure = Closure(name, self.table(name))
        else:
            closure = Closure(
                name,
                self.table(individual.class_name),
                (individual.properties, individual.relations),
                self.closure(individual.class_name),
            )
        self._closures[name] = closure
        self.statistics.closures_built += 1
        return closure

    def resolve(self, entity: str, namespace: int, name: str) -> Resolution:
        """What holds about one key of an entity, without building a closure when facts suffice.

        An individual's key that no conditional default concludes is settled by its own
        literals and its class table alone; anything else goes through its closure.
        """
        closure = self._closures.get(entity)
        if closure is not None:
            return closure.resolve(namespace, name)
        individual = self.taxonomy.individuals.get(entity)
        if individual is None:
            return self.closure(entity).resolve(namespace, name)
        table = self.table(individual.class_name)
        own_statements = individual.statements(_KINDS[namespace])
        if name in table.groups[namespace] or any(
            type(s) is not Literal for s in own_statements
        ):
            return self.closure(entity).resolve(namespace, name)
        own = [s for s in own_statements if isinstance(s, Literal) and s.name == name]
        if not own:
            return table.facts[namespace].get(name, EMPTY)
        return resolve_levels((effective(own), *table.levels[namespace].get(name, ())))

    def children(self) -> dict[str, list[str]]:
        """Direct subclasses of every class."""
        if self._children is None:
            self._children = self.taxonomy.children_map()
        return self._children

    def class_extension(self, class_name: str) -> tuple[str, ...]:
        """Individuals of a class and its subclasses: its own first, then depth first."""
        found = self._extensions.get(class_name)
        if found is not None:
            return found
        self.taxonomy.class_node(class_name)
        children = self.children()
        members: list[str] = []
        stack = [class_name]
        while stack:
            current = stack.pop()
            members.extend(self.taxonomy.classes[current].individuals)
            stack.extend(reversed(children[current]))
        result = tuple(members)
        self._extensions[class_name] = result
        self.statistics.extensions_built += 1
        return result

    # -- invalidation ----------------------------------------------------------------------

    def invalidate(self, touched: Touched) -> int:
        """Drop every cached item that depends on what ``touched`` names; returns how many."""
        dropped = 0
        taxonomy = self.taxonomy
        if touched.structure:
            self._children = None
        for class_name in sorted(touched.classes):
            if class_name not in taxonomy.classes:
                dropped += self._drop_class(class_name)
                continue
            for member in self._subtree(class_name):
                dropped += self._drop_class(member)
                for individual in taxonomy.classes[member].individuals:
                    dropped += self._closures.pop(individual, None) is not None
        for individual in sorted(touched.individuals):
            dropped += self._closures.pop(individual, None) is not None
        for class_name in sorted(touched.membership):
            if class_name not in taxonomy.classes:
                dropped += self._extensions.pop(class_name, None) is not None
                continue
            for ancestor in taxonomy.lineage(class_name):
                dropped += self._extensions.pop(ancestor, None) is not None
        self.statistics.dropped += dropped
        self.statistics.last_dropped = dropped
        self.statistics.by_update.append(dropped)
        return dropped

    def clear(self) -> None:
        """Drop every cache (used by benchmarks to measure cold queries)."""
        self._tables.clear()
        self._closures.clear()
        self._extensions.clear()
        self._children = None

    def cached(self) -> tuple[int, int, int]:
        """How many tables, closures and extensions are cached now."""
        return len(self._tables), len(self._closures), len(self._extensions)

    def _drop_class(self, class_name: str) -> int:
        dropped = int(self._tables.pop(class_name, None) is not None)
        dropped += self._closures.pop(class_name, None) is not None
        return dropped

    def _subtree(self, class_name: str) -> list[str]:
        children = self.children()
        order = []
        stack = [class_name]
        while stack:
            current = stack.pop()
            order.append(current)
            stack.extend(children.get(current, ()))
        return order
