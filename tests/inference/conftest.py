"""The issue's three shelves (drinks, food, bread) as a KB and a line of positions."""

from __future__ import annotations

import math
from collections.abc import Callable

import pytest

from homebot.inference import USER, Inventory
from homebot.knowledge import KnowledgeBase

THREE_SHELVES = """[ class(top,none,[],[],[]),
class(entity,top,[],[],[]),
class(shelf,entity,[],[],[
  [id=>s1,[[holds=>drink,0],[place=>'shelf 1',0],[name=>'shelf 1',0]],[]],
  [id=>s2,[[holds=>food,0],[place=>'shelf 2',0],[name=>'shelf 2',0]],[]],
  [id=>s3,[[holds=>bread,0],[place=>'shelf 3',0],[name=>'shelf 3',0]],[]]]),
class(product,entity,[],[],[]),
class(drink,product,[],[[loc=>s1,0]],[[id=>coke,[],[]],[id=>heineken,[],[]]]),
class(food,product,[],[[loc=>s2,0]],[[id=>noodles,[],[]],[id=>kellogs,[],[]]]),
class(bread,product,[],[[loc=>s3,0]],[[id=>bisquits,[],[]]])
]"""

# Shelves along a corridor, the client by the first one.
POSITIONS = {"s1": (0.0, 0.0), "s2": (4.0, 0.0), "s3": (10.0, 0.0), USER: (0.0, -4.0)}


def line_distance(a: str, b: str) -> float:
    return math.dist(POSITIONS[a], POSITIONS[b])


@pytest.fixture
def three_shelves() -> Inventory:
    return Inventory(KnowledgeBase.from_text(THREE_SHELVES))


@pytest.fixture
def distance() -> Callable[[str, str], float]:
    return line_distance
