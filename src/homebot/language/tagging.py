"""Tagging: normalised tokens to recognised units, with people's descriptions composed."""

from __future__ import annotations

from homebot.language import lexicon
from homebot.language.normalise import QUOTE_MARK, Normalised
from homebot.language.vocabulary import Token, Vocabulary

__all__ = ["compose_people", "tag"]

_RELATIVE = frozenset({"who", "that", "which", "is", "are", "currently", "right", "just"})


def tag(normalised: Normalised, vocabulary: Vocabulary) -> list[Token]:
    """Longest-match the tokens against the vocabulary; drop fillers; compose people."""
    tokens = normalised.tokens
    tagged: list[Token] = []
    position = 0
    while position < len(tokens):
        word = tokens[position]
        if word.startswith(QUOTE_MARK) and word[len(QUOTE_MARK):].isdigit():
            number = int(word[len(QUOTE_MARK):])
            quote = normalised.quotes[number] if number < len(normalised.quotes) else ""
            tagged.append(Token("quote", quote, quote))
            position += 1
            continue
        found: Token | None = None
        length = min(vocabulary.longest, len(tokens) - position)
        while length > 0:
            found = vocabulary.index.get(tuple(tokens[position:position + length]))
            if found is not None:
                break
            length -= 1
        if found is None:
            tagged.append(Token("word", word, word))
            position += 1
            continue
        if found.kind != "filler":
            text = " ".join(tokens[position:position + length])
            tagged.append(Token(found.kind, found.value, text))
        position += length
    return compose_people(tagged)


def compose_people(tokens: list[Token]) -> list[Token]:
    """Merge person nouns with their postures, gestures and clothes into person tokens.

    Names become ``person`` tokens ``{"name": N}``; "the waving person", "a person
    pointing to the left", "the person wearing a red jacket" become descriptions.
    Attributes that stand apart ("people in the kitchen are waving") stay as they are;
    the clause builder attaches them to the nearest person.
    """
    result: list[Token] = []
    position = 0
    while position < len(tokens):
        token = tokens[position]
        if token.kind == "entity" and len(token.value) == 1 and token.value[0].kind == "person":
            result.append(Token("person", {"name": token.value[0].name}, token.text))
            position += 1
            continue
        if token.kind != "person_noun":
            result.append(token)
            position += 1
            continue
        description: dict[str, str] = {}
        while result and result[-1].kind in {"posture", "gesture"}:
            attribute = result.pop()
            description.setdefault(attribute.kind, attribute.value)
        position = _attributes_after(tokens, position + 1, description)
        result.append(Token("person", description, token.text))
    return result


def _attributes_after(tokens: list[Token], position: int, description: dict[str, str]) -> int:
    """Read attributes following a person noun into ``description``; the next position."""
    while position < len(tokens):
        token = tokens[position]
        if token.kind == "word" and token.value in _RELATIVE:
            position += 1
            continue
        if token.kind in {"posture", "gesture"}:
            description.setdefault(token.kind, token.value)
            position += 1
            continue
        clothes_at = _clothes_position(tokens, position)
        if clothes_at is None:
            break
        description.setdefault("clothes", tokens[clothes_at].value)
        position = clothes_at + 1
    return position


def _clothes_position(tokens: list[Token], position: int) -> int | None:
    """Where the clothes of "wearing a red coat" / "in a red coat" are, if they start here."""
    token = tokens[position]
    if token.kind == "clothes":
        return position
    opens = token.kind == "wearing" or (token.kind == "prep" and token.value in {"in", "with"})
    if not opens:
        return None
    following = position + 1
    while following < len(tokens) and tokens[following].kind == "word" and (
            tokens[following].value in lexicon.ARTICLES):
        following += 1
    if following < len(tokens) and tokens[following].kind == "clothes":
        return following
    return None
