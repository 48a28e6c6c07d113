"""The supermarket client's request: which product, whether it may be served, the fetch task."""

from __future__ import annotations

from homebot.inference.inventory import Inventory
from homebot.task import Step, Task

__all__ = ["age_in_words", "fetch_task", "requested_product"]

_UNITS = {"zero": 0, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6,
          "seven": 7, "eight": 8, "nine": 9, "ten": 10, "eleven": 11, "twelve": 12,
          "thirteen": 13, "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17,
          "eighteen": 18, "nineteen": 19}
_TENS = {"twenty": 20, "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "seventy": 70,
         "eighty": 80, "ninety": 90}


def age_in_words(answer: str | None) -> int | None:
    """The age in an answer such as 'twenty five', 'I am 25' or 'forty-two years'."""
    if not answer:
        return None
    total: int | None = None
    for word in answer.lower().replace("-", " ").split():
        word = word.strip(".,!?")
        if word.isdigit():
            return int(word)
        if word in _TENS:
            total = (total or 0) + _TENS[word]
        elif word in _UNITS:
            total = (total or 0) + _UNITS[word]
    return total


def requested_product(inventory: Inventory, words: str) -> str | None:
    """The product a request names: a product itself, or the first of a named class (beer)."""
    for word in words.lower().replace("?", " ").replace(".", " ").split():
        if word in inventory.products:
            return word
        singular = word[:-1] if word.endswith("s") else word
        for name in (word, singular):
            if name in inventory.kb.taxonomy.classes and name not in ("top", "entity"):
                members = [p for p in inventory.products if inventory.member(p, name)]
                if members:
                    return members[0]
    return None


def fetch_task(inventory: Inventory, product: str, client: str = "operator") -> Task:
    """The GPSR scheme for 'bring me X': to the shelf the KB believes, take, back, hand over.

    ``kb_get_shelf_of_object`` is the KB lookup; when the KB does not know where
    the product is, the take behaviour fails at once and the inference cycle starts.
    """
    shelf = inventory.believed_at(product)
    steps = []
    if shelf in inventory.shelves:
        steps.append(Step("navigate", {"to": inventory.place(shelf)}))
    steps += [Step("pick", {"object": product}), Step("navigate", {"to": client}),
              Step("give", {"person": client, "object": product})]
    return Task(tuple(steps), f"bring the {product} to the client")
