"""Whatever a world file holds, loading it succeeds or raises ``HomebotError``, never a crash."""

from __future__ import annotations

import copy
from typing import Any

import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from homebot.errors import HomebotError
from homebot.world import World, shipped_world_path

_TEXT = shipped_world_path("supermarket").read_text(encoding="utf-8")
_DATA = yaml.safe_load(_TEXT)
_NOISE = st.text(alphabet=st.sampled_from(list("[]{}:,-'\"#&*!|>?% \n\tabcxyz019.é😀")),
                 max_size=12)
_SCALARS = (st.none() | st.booleans() | st.integers(-10**6, 10**6)
            | st.floats(allow_nan=True, allow_infinity=True) | st.text(max_size=10))
_VALUES = st.recursive(_SCALARS, lambda inner: st.lists(inner, max_size=4)
                       | st.dictionaries(st.text(max_size=6) | st.integers(), inner, max_size=4),
                       max_leaves=10)


def _loads(text: str) -> None:
    try:
        World.from_yaml_text(text, "fuzz.yaml")
    except HomebotError as error:
        assert str(error)


@settings(max_examples=200, deadline=None)
@given(st.integers(0, len(_TEXT)), st.integers(0, 40), _NOISE)
def test_a_damaged_world_file_is_rejected_with_a_homebot_error(start: int, cut: int,
                                                               noise: str) -> None:
    _loads(_TEXT[:start] + noise + _TEXT[start + cut:])


@settings(max_examples=300, deadline=None)
@given(st.data(), _VALUES)
def test_a_wrong_value_anywhere_is_rejected_with_a_homebot_error(data: st.DataObject,
                                                                 value: Any) -> None:
    world = copy.deepcopy(_DATA)
    node: Any = world
    while True:  # walk down to a random field or item, then replace it
        keys = list(node) if isinstance(node, dict) else list(range(len(node)))
        key = data.draw(st.sampled_from(keys))
        if not isinstance(node[key], (dict, list)) or not node[key] or data.draw(st.booleans()):
            node[key] = value
            break
        node = node[key]
    _loads(yaml.safe_dump(world, allow_unicode=True))


@settings(max_examples=100, deadline=None)
@given(_VALUES)
def test_any_yaml_document_is_loaded_or_rejected(value: Any) -> None:
    _loads(yaml.safe_dump(value, allow_unicode=True))
