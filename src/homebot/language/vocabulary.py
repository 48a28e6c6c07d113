"""The words the parser knows: a world's names, their synonyms, and the fixed lexicon."""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from homebot.errors import LanguageError
from homebot.language import lexicon
from homebot.text import fold

__all__ = ["SYNONYMS", "Entity", "Token", "Vocabulary", "names_in_world", "phrase_tokens",
           "progressive"]

# Other words for common places and things; used only when the target exists in the
# world and the word is not itself a name there.
SYNONYMS: tuple[tuple[str, str], ...] = (
    ("fridge", "refrigerator"), ("refrigerator", "fridge"), ("couch", "sofa"),
    ("sofa", "couch"), ("coke", "cola"), ("cupboard", "cabinet"),
    ("television stand", "tv stand"), ("tv", "tv stand"), ("trash can", "trashbin"),
    ("trash bin", "trashbin"), ("bin", "trashbin"), ("garbage can", "trashbin"),
    ("rubbish bin", "trashbin"), ("wastebasket", "waste basket"), ("lounge", "living room"),
    ("sitting room", "living room"), ("livingroom", "living room"), ("study", "office"),
    ("dining table", "kitchen table"), ("nightstand", "bedside table"),
    ("night stand", "bedside table"), ("bookcase", "bookshelf"), ("shelves", "shelf"),
    ("front door", "entrance"), ("way out", "exit"), ("plant", "potted plant"),
    ("dish washer", "dishwasher"), ("rack", "storage rack"), ("coffee", "coffee grounds"),
    ("rubik cube", "rubiks cube"), ("rubiks cube", "rubik cube"), ("juice", "orange juice"),
    ("crackers", "cheezit"), ("cheez it", "cheezit"), ("wine", "red wine"),
    ("soap dispenser", "soap"), ("football", "soccer ball"), ("telly", "tv stand"),
    ("bedside", "bedside table"), ("wardrobe", "closet"), ("closet", "wardrobe"),
    ("mug", "cup"), ("cup", "mug"), ("chips", "crisps"), ("crisps", "chips"),
    ("cookies", "biscuits"), ("biscuits", "cookies"), ("cookie", "biscuits"),
    ("teddy", "teddy bear"), ("brew", "beer"), ("charger", "phone charger"),
    ("remote", "remote control"), ("tv remote", "remote control"),
    ("ball", "tennis ball"), ("dish soap", "soap"), ("soap", "detergent"),
    ("washing up liquid", "detergent"), ("study", "office"), ("office", "study"),
    ("corridor", "hallway"), ("hallway", "corridor"), ("hall", "hallway"),
    ("night table", "bedside table"), ("night table", "nightstand"),
    ("bedside table", "nightstand"), ("nightstand", "bedside table"),
    ("kitchen table", "dining table"), ("couch", "sofa"), ("settee", "sofa"),
    ("settee", "couch"), ("frame", "picture frame"), ("photo frame", "picture frame"),
    ("soft drink", "cola"), ("telly", "tv stand"), ("bookcase", "bookshelf"),
    ("fizzy water", "sparkling water"), ("juice", "apple juice"), ("lemon soda", "lemonade"),
)

_SPLIT = re.compile(r"[\W_]+")


def phrase_tokens(text: str) -> tuple[str, ...]:
    """The normalised tokens of a name or phrase: folded (``homebot.text.fold``: no case,
    no accents), apostrophes dropped, split at anything that is not a letter or digit."""
    return tuple(token for token in _SPLIT.split(fold(text).replace("'", "")) if token)


@dataclass(frozen=True, slots=True)
class Entity:
    """Something in the world a phrase can name: kind is person, room, placement,
    object, category or door; ``name`` is its canonical name in the world."""

    kind: str
    name: str


@dataclass(frozen=True, slots=True)
class Token:
    """One recognised unit of a command: a word, an entity, a verb, a topic...

    ``kind`` is one of word, sep, entity, action, topic, info, property, posture,
    gesture, clothes, wearing, person_noun, pronoun, me, count, generic, quote.
    For entity tokens ``value`` is a tuple of candidate entities (several when the
    phrase is ambiguous, like "table"); ``text`` is the words as heard.
    """

    kind: str
    value: Any
    text: str


@dataclass(frozen=True)
class Vocabulary:
    """Names from one world plus the fixed lexicon, indexed by phrase.

    Build it with ``Vocabulary.from_world(world)`` or ``Vocabulary.from_names(...)``.
    """

    rooms: tuple[str, ...]
    placements: Mapping[str, str]  # placement -> room
    objects: Mapping[str, str]  # object -> category
    categories: Mapping[str, str]  # category -> plural
    people: tuple[str, ...]
    doors: tuple[str, ...] = ()
    index: Mapping[tuple[str, ...], Token] = field(default_factory=dict)
    words: frozenset[str] = frozenset()
    spelling_choices: tuple[str, ...] = ()
    name_choices: tuple[str, ...] = ()
    longest: int = 1

    @classmethod
    def from_world(cls, world: Any) -> Vocabulary:
        """The vocabulary of a ``homebot.world.World``."""
        return cls.from_names(**names_in_world(world))

    @classmethod
    def from_names(cls, *, rooms: Iterable[str], placements: Mapping[str, str],
                   objects: Mapping[str, str], categories: Mapping[str, str],
                   people: Iterable[str], doors: Iterable[str] = ()) -> Vocabulary:
        """A vocabulary from plain names (placement -> room, object -> category,
        category -> plural). Raises ``LanguageError`` for a name with no letters."""
        rooms, people, doors = tuple(rooms), tuple(people), tuple(doors)
        for name in (*rooms, *placements, *objects, *categories, *people, *doors):
            if not phrase_tokens(name):
                raise LanguageError(f"the name {name!r} has no letters; rename it")
        index = _build_index(rooms, placements, objects, categories, people, doors)
        words = frozenset(word for phrase in index for word in phrase)
        targets = {word for phrase, token in index.items() if token.kind != "filler"
                   for word in phrase}
        return cls(rooms=rooms, placements=MappingProxyType(dict(placements)),
                   objects=MappingProxyType(dict(objects)),
                   categories=MappingProxyType(dict(categories)), people=people, doors=doors,
                   index=MappingProxyType(index), words=words,
                   spelling_choices=tuple(sorted(w for w in targets
                                                 if len(w) >= 3 and w.isalpha())),
                   name_choices=tuple(sorted({w for name in people
                                              for w in phrase_tokens(name)})),
                   longest=max(len(phrase) for phrase in index))

    def kind_of(self, name: str) -> str | None:
        """Which kind of entity ``name`` is in this world, if any."""
        if name in self.placements:
            return "placement"
        if name in self.rooms:
            return "room"
        if name in self.objects:
            return "object"
        if name in self.categories:
            return "category"
        if name in self.people:
            return "person"
        if name in self.doors:
            return "door"
        return None

    def objects_of(self, category: str) -> list[str]:
        """The objects of a category, in world order."""
        return [name for name, of in self.objects.items() if of == category]

    def placements_in(self, room: str) -> list[str]:
        return [name for name, where in self.placements.items() if where == room]


def _build_index(rooms: tuple[str, ...], placements: Mapping[str, str],
                 objects: Mapping[str, str], categories: Mapping[str, str],
                 people: tuple[str, ...], doors: tuple[str, ...]) -> dict[tuple[str, ...], Token]:
    index: dict[tuple[str, ...], Token] = {}
    _add_lexicon(index)
    named: dict[tuple[str, ...], list[Entity]] = {}
    groups: list[tuple[str, Iterable[str]]] = [
        ("person", people), ("room", rooms), ("placement", placements), ("object", objects),
        ("category", categories), ("door", doors)]
    for kind, names in groups:
        for name in names:
            named.setdefault(phrase_tokens(name), []).append(Entity(kind, name))
    for category, plural in categories.items():
        named.setdefault(phrase_tokens(plural), []).append(Entity("category", category))
    derived: dict[tuple[str, ...], list[Entity]] = {}
    for kind, names in groups[1:5]:
        for name in names:
            for variant in _variants(name, kind):
                derived.setdefault(variant, []).append(Entity(kind, name))
    for word, target in SYNONYMS:
        target_kind = _kind(target, rooms, placements, objects)
        if target_kind:
            derived.setdefault(phrase_tokens(word), []).append(Entity(target_kind, target))
    for phrase, candidates in _category_phrases(categories).items():
        derived.setdefault(phrase, []).extend(candidates)
    for phrase, entities in derived.items():
        if phrase not in named:
            unique = list(dict.fromkeys(entities))
            index[phrase] = Token("entity", tuple(unique), " ".join(phrase))
    for phrase, entities in named.items():
        # An object and a category of the same name: the object is more specific.
        kinds = {entity.kind for entity in entities}
        chosen = [e for e in entities if e.kind != "category"] if "object" in kinds else entities
        index[phrase] = Token("entity", tuple(dict.fromkeys(chosen)), " ".join(phrase))
    return index


def _kind(name: str, rooms: tuple[str, ...], placements: Mapping[str, str],
          objects: Mapping[str, str]) -> str | None:
    if name in placements:
        return "placement"
    if name in rooms:
        return "room"
    if name in objects:
        return "object"
    return None


def _variants(name: str, kind: str) -> Iterable[tuple[str, ...]]:
    """Other ways to say a name: joined or split words, singular or plural, head noun."""
    tokens = phrase_tokens(name)
    if len(tokens) > 1:
        yield ("".join(tokens),)
        if kind == "placement" and tokens[-1] not in {"room", "stand"}:
            yield (tokens[-1],)  # "table" for "kitchen table": ambiguous unless unique
    last = tokens[-1]
    if last.endswith("s") and len(last) > 3 and kind in {"placement", "object"}:
        yield (*tokens[:-1], last[:-1])
    if kind == "object" and not last.endswith("s"):
        plural = last + ("es" if last.endswith(("sh", "ch", "x")) else "s")
        yield (*tokens[:-1], plural)
    if kind == "category" and " " in name:
        yield (tokens[0],)


def _category_phrases(categories: Mapping[str, str]) -> dict[tuple[str, ...], list[Entity]]:
    phrases: dict[tuple[str, ...], list[Entity]] = {}
    for phrase, candidates in lexicon.CATEGORY_PHRASES:
        known = [category for category in candidates if category in categories]
        if known:
            phrases[phrase_tokens(phrase)] = [Entity("category", known[0])]
    return phrases


def _add_lexicon(index: dict[tuple[str, ...], Token]) -> None:
    tables: list[tuple[str, Iterable[tuple[str, Any]]]] = [
        ("filler", ((phrase, None) for phrase in lexicon.FILLERS)),
        ("action", lexicon.ACTIONS), ("topic", lexicon.TOPICS), ("info", lexicon.INFO_WORDS),
        ("property", lexicon.PROPERTIES), ("posture", lexicon.POSTURES),
        ("sep", ((phrase, "then") for phrase in lexicon.SEPARATORS)),
        ("wearing", ((phrase, "wearing") for phrase in lexicon.WEARING_MARKERS)),
        ("prep", lexicon.PREPOSITIONS),
        ("person_noun", ((word, word) for word in lexicon.PERSON_NOUNS)),
        ("generic", ((word, "object") for word in lexicon.GENERIC_OBJECT_WORDS)),
        ("me", (("me", "operator"), ("myself", "operator"), ("us", "operator"))),
        ("pronoun", (("it", "it"), ("them", "them"), ("him", "them"), ("her", "them"),
                     ("they", "them"), ("those", "them"), ("she", "them"), ("he", "them"))),
        ("quantity", lexicon.QUANTITIES),
        ("count", (("how many", "count"), ("the number of", "count"),
                   ("the amount of", "count"), ("number of", "count"))),
    ]
    for kind, pairs in tables:
        for phrase, value in pairs:
            index[phrase_tokens(phrase)] = Token(kind, value, phrase)
    for phrase, value in lexicon.ACTIONS:
        first, *rest = phrase_tokens(phrase)
        index.setdefault((progressive(first), *rest), Token("action", value, phrase))
    index[(",",)] = Token("sep", "then", ",")
    for phrase, value in lexicon.GESTURES:
        for variant in _possessive_variants(phrase):
            index[variant] = Token("gesture", value, phrase)
    for colour, colour_value in lexicon.CLOTHING_COLOURS:
        for garment, garment_value in lexicon.CLOTHING_GARMENTS:
            index[phrase_tokens(f"{colour} {garment}")] = Token(
                "clothes", f"{colour_value} {garment_value}", f"{colour} {garment}")
    for garment, garment_value in lexicon.CLOTHING_GARMENTS:
        index[phrase_tokens(garment)] = Token("clothes", garment_value, garment)


def progressive(verb: str) -> str:
    """The -ing form of a verb: bring -> bringing, take -> taking, put -> putting."""
    vowels = "aeiou"
    if verb.endswith("e") and not verb.endswith("ee"):
        return verb[:-1] + "ing"
    if (3 <= len(verb) <= 4 and verb[-1] not in vowels + "wxy" and verb[-2] in vowels
            and verb[-3] not in vowels and not (len(verb) == 4 and verb[0] in vowels)):
        return verb + verb[-1] + "ing"
    return verb + "ing"


def _possessive_variants(phrase: str) -> list[tuple[str, ...]]:
    tokens = phrase_tokens(phrase)
    if "their" not in tokens:
        return [tokens]
    at = tokens.index("their")
    return [(*tokens[:at], word, *tokens[at + 1:]) for word in lexicon.POSSESSIVES]


def names_in_world(world: Any) -> dict[str, Any]:
    """``Vocabulary.from_names``'s arguments for a ``homebot.world.World``, as plain data."""
    objects = {name: model.category for name, model in world.objects.items()}
    categories = {name: model.plural for name, model in world.categories.items()}
    for category in objects.values():
        categories.setdefault(category, world.plural_of(category))
    return {"rooms": list(world.rooms), "people": list(world.people), "objects": objects,
            "placements": {name: placement.room for name, placement in world.placements.items()},
            "categories": categories, "doors": list(world.doors)}
