"""The KB service: the paper's eight queries, value lookups, abduction and updates."""

from __future__ import annotations

from pathlib import Path

from homebot.errors import KnowledgeError
from homebot.knowledge import coherence
from homebot.knowledge.abduction import Explanation, explain, matches_pattern
from homebot.knowledge.closure import antecedent_holds
from homebot.knowledge.model import ANY, Literal, Preference, Taxonomy, Value
from homebot.knowledge.reasoner import Reasoner, Touched
from homebot.knowledge.tables import NAMESPACES, PROPERTY, RELATION, Resolution
from homebot.knowledge.terms import parse_statement

__all__ = ["UNKNOWN", "Answer", "KnowledgeBase", "shipped_kb_names", "shipped_kb_path"]

_DATA_TOKEN = "$DATA"

#: The answer when neither a statement nor its negation holds (no closed world).
UNKNOWN = "unknown"

#: ``"yes"``, ``"no"``, ``"unknown"``, or the value itself.
Answer = Value


class KnowledgeBase:
    """A non-monotonic KB: queries over the closure of inheritance, defaults and preferences.

    Answers are cached per class and per individual; ``apply`` runs an update and drops
    only the cached answers that depend on what it touched.
    """

    __slots__ = ("reasoner", "taxonomy")

    def __init__(self, taxonomy: Taxonomy) -> None:
        coherence.check(taxonomy)
        self.taxonomy = taxonomy
        self.reasoner = Reasoner(taxonomy)

    # -- loading -------------------------------------------------------------------------

    @classmethod
    def from_file(cls, path: str | Path) -> KnowledgeBase:
        """Load a ``.yaml``/``.yml`` file in the YAML form, anything else in the paper's syntax."""
        from homebot.knowledge.syntax import read_kb
        from homebot.knowledge.yaml_form import read_kb_yaml

        path = Path(path)
        if path.suffix.lower() in (".yaml", ".yml"):
            return cls(read_kb_yaml(path))
        return cls(read_kb(path))

    @classmethod
    def load(cls, spec: str | Path) -> KnowledgeBase:
        """Load a KB file, a store (``.db``), ``$DATA/kb/NAME.kb`` or a shipped KB by name."""
        path = shipped_kb_path(spec)
        if path.suffix.lower() in (".db", ".sqlite", ".sqlite3"):
            from homebot.knowledge.store import KnowledgeStore

            with KnowledgeStore.open(path) as store:
                return store.kb
        return cls.from_file(path)

    @classmethod
    def from_text(cls, text: str, source: str = "<text>") -> KnowledgeBase:
        """Parse KB text in the paper's syntax."""
        from homebot.knowledge.syntax import read_kb_text

        return cls(read_kb_text(text, source))

    def to_text(self) -> str:
        """The KB in the paper's syntax."""
        from homebot.knowledge.syntax import write_kb_text

        return write_kb_text(self.taxonomy)

    # -- the eight services of §6 ------------------------------------------------------------

    def class_extension(self, class_name: str) -> list[str]:
        """The individuals of a class and of all its subclasses (``top``: everyone)."""
        return list(self.reasoner.class_extension(class_name))

    def property_extension(self, prop: str | Literal) -> list[tuple[str, Answer]]:
        """``(individual, answer)`` for every individual whose answer is not unknown."""
        pattern = _pattern(prop)
        result = []
        resolve = self.reasoner.resolve
        for individual in self.reasoner.class_extension("top"):
            answer = _answer(pattern, resolve(individual, PROPERTY, pattern.name))
            if answer != UNKNOWN:
                result.append((individual, answer))
        return result

    def relation_extension(self, relation: str | Literal) -> list[tuple[str, list[Value]]]:
        """``(individual, objects)`` for every individual standing in the relation."""
        pattern = _pattern(relation)
        result = []
        for individual in self.reasoner.class_extension("top"):
            resolution = self.reasoner.resolve(individual, RELATION, pattern.name)
            objects: list[Value] = []
            for literal in resolution.literals:
                if literal.negated or literal.value is None:
                    continue
                if matches_pattern(pattern, literal) or pattern.value is None:
                    objects.extend(self._objects(literal.value))
            if objects:
                result.append((individual, objects))
        return result

    def explanation_extension(self, prop: str | Literal) -> list[tuple[str, Explanation]]:
        """``(individual, explanation)`` for every individual with an explanation of ``prop``."""
        pattern = _pattern(prop)
        result = []
        for individual in self.reasoner.class_extension("top"):
            for explanation in explain(self.reasoner.closure(individual)):
                if matches_pattern(pattern, explanation.consequent):
                    result.append((individual, explanation))
        return result

    def classes_of_individual(self, individual: str) -> list[str]:
        """The individual's class and all its ancestors up to ``top``."""
        return self.taxonomy.lineage(self.taxonomy.individual(individual).class_name)

    def properties_of_individual(self, individual: str) -> list[Literal]:
        """Every property that holds: stated ones by specificity, then concluded ones."""
        self.taxonomy.individual(individual)
        return self.holding(individual, PROPERTY)

    def relations_of_individual(self, individual: str) -> list[Literal]:
        """Every relation that holds; a class as object stands for its individuals."""
        self.taxonomy.individual(individual)
        return [self._expand(literal) for literal in self.holding(individual, RELATION)]

    def explanation_of_individual(self, individual: str) -> list[Explanation]:
        """The most preferred explanation of each property and relation that holds."""
        self.taxonomy.individual(individual)
        return explain(self.reasoner.closure(individual))

    # -- lookups -----------------------------------------------------------------------------

    def value(self, entity: str, prop: str | Literal) -> Answer:
        """``yes``/``no``/``unknown`` for ``p=>v`` or ``not(...)``; the value for a bare name.

        A bare name with a value (``live``) answers the value; without one (``fly``)
        ``yes`` or ``no``. Properties are looked up first, then relations.
        """
        pattern = _pattern(prop)
        resolution = self._resolve_either(entity, pattern.name)
        if pattern.value is None and not pattern.negated:
            return _answer(pattern, resolution)
        literals = resolution.literals
        holds, _ = antecedent_holds(pattern, literals, None)
        if not holds:
            literals = tuple(self._expand(literal) for literal in literals)
            holds, _ = antecedent_holds(pattern, literals, None)
        if holds:
            return "yes"
        refuted, _ = antecedent_holds(pattern.negation(), literals, None)
        if refuted or (resolution.decisive and not pattern.negated and pattern.value is not None):
            return "no"
        if pattern.negated and any(not x.negated for x in literals):
            return "no"
        return UNKNOWN

    def values(self, entity: str, prop: str | Literal) -> list[Value]:
        """All values of a property in preference order (Appendix B.2).

        Stated values come first, then the value of every conditional default whose
        antecedents hold, in priority order, each value once.
        """
        pattern = _pattern(prop)
        closure = self.reasoner.closure(entity)
        result: list[Value] = []
        for namespace in NAMESPACES:
            facts = closure.facts(namespace, pattern.name)
            excluded = [x.value for x in facts.literals if x.negated and x.value is not None]
            for literal in facts.literals:
                if not literal.negated and literal.value is not None:
                    _add(result, literal.value)
            if facts.decisive and not any(x.value is not None for x in facts.literals):
                continue
            for _rule, conclusion, _binding in closure.firing((namespace, pattern.name)):
                if conclusion.negated or conclusion.value is None:
                    continue
                if conclusion.value not in excluded:
                    _add(result, conclusion.value)
            if result:
                break
        return result

    def holding(self, entity: str, namespace: int) -> list[Literal]:
        """What holds about a class or individual in one namespace, in output order."""
        return list(self.reasoner.closure(entity).holding(namespace))

    def explanations(self, entity: str) -> list[Explanation]:
        """Explanations for a class or an individual (``explain`` on the CLI)."""
        return explain(self.reasoner.closure(entity))

    def preferences(self, entity: str) -> list[Preference]:
        """The conditional defaults that apply to an entity, in priority order."""
        return [rule.preference for rule in self.reasoner.closure(entity).rules]

    # -- updates -------------------------------------------------------------------------------

    def apply(self, update: object) -> Touched:
        """Run an update (``homebot.knowledge.updates``); the KB stays coherent or is unchanged."""
        from homebot.knowledge.updates import Update

        if not isinstance(update, Update):
            raise KnowledgeError(f"{update!r} is not a knowledge-base update")
        touched = update.apply(self.taxonomy)
        self.reasoner.invalidate(touched)
        return touched

    # -- helpers ---------------------------------------------------------------------------------

    def _resolve_either(self, entity: str, name: str) -> Resolution:
        found = self.reasoner.resolve(entity, PROPERTY, name)
        if not found.literals:
            found = self.reasoner.resolve(entity, RELATION, name)
        return found

    def _objects(self, value: Value) -> list[Value]:
        if isinstance(value, str) and value in self.taxonomy.classes:
            return list(self.reasoner.class_extension(value))
        if isinstance(value, tuple):
            return [item for part in value for item in self._objects(part)]
        return [value]

    def _expand(self, literal: Literal) -> Literal:
        value = literal.value
        if value is None:
            return literal
        if (isinstance(value, str) and value in self.taxonomy.classes) or isinstance(value, tuple):
            return literal.with_value(tuple(self._objects(value)))
        return literal

    def __repr__(self) -> str:
        return f"KnowledgeBase({self.taxonomy!r})"


def _data_directory() -> Path:
    return Path(__file__).resolve().parent.parent / "data"


def shipped_kb_names() -> list[str]:
    """The KBs shipped in ``homebot/data/kb`` (``butler``, ``animals``, ...)."""
    return sorted(path.stem for path in (_data_directory() / "kb").glob("*.kb"))


def shipped_kb_path(spec: str | Path) -> Path:
    """The file a KB argument names: a path, ``$DATA/...``, or a shipped KB's name."""
    text = str(spec)
    if text.startswith(_DATA_TOKEN):
        return _data_directory() / text[len(_DATA_TOKEN) :].lstrip("/")
    path = Path(text)
    if path.exists():
        return path
    shipped = _data_directory() / "kb" / f"{text}.kb"
    if "/" not in text and shipped.is_file():
        return shipped
    names = ", ".join(shipped_kb_names())
    raise KnowledgeError(f"no KB file '{text}'; give a path or a shipped KB name ({names})")


def _pattern(prop: str | Literal) -> Literal:
    if isinstance(prop, Literal):
        return prop
    if not isinstance(prop, str) or not prop.strip():
        raise KnowledgeError("expected a property such as fly, live=>mexico or not(fly)")
    statement = parse_statement(prop, source=f"'{prop}'")
    if isinstance(statement, Preference):
        raise KnowledgeError(f"expected a property, not the conditional default {statement}")
    return statement


def _answer(pattern: Literal, resolution: Resolution) -> Answer:
    for literal in resolution.literals:
        if literal.negated and literal.value is None:
            return "no" if not pattern.negated else "yes"
        if not literal.negated:
            if pattern.negated:
                return "no"
            return "yes" if literal.value is None else literal.value
    return UNKNOWN


def _add(values: list[Value], value: Value) -> None:
    if value not in values and value != ANY:
        values.append(value)
